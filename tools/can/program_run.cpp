#include "tools/can/program_run.hpp"

#include <cmath>
#include <optional>
#include <utility>

#include "firmware/can/param_table.hpp"
#include "tools/can/path_telemetry.hpp"
#include "tools/gcode/probe_outcome.hpp"

namespace tnv::can_host {

namespace {

const can::ParamDef& param(const char* name) { return *can::find_param(name); }

// Where the first element starts: the reference the node holds, from the telemetry.
fw::motion::PlanePoint standing_reference(NodeClient& client, PathTelemetry& telemetry) {
  const std::size_t seen = telemetry.samples().size();
  if (!client.pump_until([&] { return telemetry.samples().size() >= seen + 2; }, Micros{500'000}))
    throw RequestError(RequestError::Kind::timeout, "no TLM_POSITION_X / _Y pair from node " +
                                                        std::to_string(client.node()) + " within 500 ms");
  return *telemetry.last_reference();
}

struct Prepared {
  gcode::GcodeProgram program;
  WireProgram wire;
};

gcode::GcodeOptions parse_options(const fw::motion::PlanePoint& start_mm, const fw::motion::MotionLimits& limits,
                                  const ProgramRunOptions& o) {
  gcode::GcodeOptions g;
  g.start_mm = start_mm;
  g.rapid_feed_mm_s = o.rapid_feed_mm_s;
  g.limits = limits;
  g.canon = o.canon;
  return g;
}

// Read before anything moves. A program that probes is read as if no probe
// tripped (each ends at its end, #5070 0): what follows a probe is read
// again from its real outcome while the program runs (stream_probing).
gcode::GcodeResult parse(const std::string& text, const fw::motion::PlanePoint& start_mm,
                         const fw::motion::MotionLimits& limits, const ProgramRunOptions& o) {
  gcode::GcodeOptions g = parse_options(start_mm, limits, o);
  g.run_probe = gcode::untouched_probe;
  return gcode::parse_gcode(text, g);
}

// A program that probes: read again as it runs; at each probe what was
// read is sent, the probe's result awaited, and the reading goes on from
// it (docs/gcode.md "Probe moves"). A probe's error stops the reading:
// nothing after it is sent.
StreamResult stream_probing(NodeClient& client, const std::string& text, const ProgramRunOptions& o,
                            const StreamOptions& so, ProgramRunResult& r) {
  WireProgram wire;
  fw::motion::PlanePoint at_mm = r.start_mm;
  std::size_t wired = 0;
  std::string wire_error;
  ProgramStreamer streamer(client, wire, so);
  gcode::GcodeOptions g = parse_options(r.start_mm, r.limits, o);
  g.run_probe = [&](const gcode::GcodeProgram& so_far) {
    gcode::ProbeRun run;
    if (!wire_append(so_far, wired, at_mm, client.node(), wire, wire_error)) {
      run.error = wire_error;
      return run;
    }
    wired = so_far.segments.size();
    const std::optional<ProbeResult> result = streamer.run_to_probe(so_far.programmed_time_s());
    if (!result) {
      run.error = "the run stopped before the probe's result";
      return run;
    }
    run = gcode::probe_run(result->outcome, so_far.segments.back().probe, result->trip_mm, result->rest_mm);
    at_mm = result->rest_mm;
    return run;
  };
  gcode::GcodeResult parsed = gcode::parse_gcode(text, g);
  if (parsed.error) {
    r.program = {};
    StreamResult out = streamer.abandon(gcode::to_string(*parsed.error));
    r.wire = std::move(wire);
    return out;
  }
  if (!wire_append(parsed.program, wired, at_mm, client.node(), wire, wire_error)) {
    r.program = {};
    StreamResult out = streamer.abandon(wire_error);
    r.wire = std::move(wire);
    return out;
  }
  r.program = std::move(parsed.program);
  StreamResult out = streamer.finish(r.program.programmed_time_s());
  r.wire = std::move(wire);
  return out;
}

// The run's telemetry, and every frame to the caller's listener too.
FrameListener both(PathTelemetry& telemetry, const FrameListener& also) {
  return [&telemetry, also](const hal::CanFrame& f, can::MessageId id) {
    telemetry.take(f, id);
    if (also) also(f, id);
  };
}

Prepared prepare(const std::string& text, const fw::motion::PlanePoint& start_mm, const fw::motion::MotionLimits& limits,
                 const ProgramRunOptions& o, std::uint8_t node) {
  gcode::GcodeResult parsed = parse(text, start_mm, limits, o);
  if (parsed.error) throw ProgramInputError(gcode::to_string(*parsed.error));
  if (parsed.program.segments.empty()) throw ProgramInputError("the program has no motion and no dwell");
  if (o.before_wire && parsed.program.probes == 0) o.before_wire(parsed.program);
  std::string error;
  std::optional<WireProgram> wire = wire_program(parsed.program, start_mm, node, error);
  if (!wire) throw ProgramInputError(error);
  return {std::move(parsed.program), std::move(*wire)};
}

}  // namespace

ProgramRunOptions with_node_tool(NodeClient& client, const ProgramRunOptions& o) {
  ProgramRunOptions out = o;
  if (!o.tool_from_node || !o.canon.from_line) return out;
  out.tool_from_node = false;  // asked once: the answer stands for this run
  const ProgramTool tool = client.program_tool();
  if (tool.known) out.canon.from_line->tool_in_spindle = tool.tool;
  return out;
}

ProgramPlan plan_gcode(NodeClient& client, const std::string& gcode_text, const ProgramRunOptions& options) {
  const ProgramRunOptions o = with_node_tool(client, options);
  ProgramPlan plan;
  plan.limits = node_motion_limits(client);
  PathTelemetry telemetry;
  client.set_listener(both(telemetry, o.on_frame));
  try {
    plan.start_mm = standing_reference(client, telemetry);
  } catch (...) {
    client.set_listener(o.on_frame);
    throw;
  }
  client.set_listener(o.on_frame);
  plan.parsed = parse(gcode_text, plan.start_mm, plan.limits, o);
  if (!plan.parsed.error && !wire_program(plan.parsed.program, plan.start_mm, client.node(), plan.wire_error))
    if (plan.wire_error.empty()) plan.wire_error = "the program cannot be sent";
  return plan;
}

fw::motion::MotionLimits node_motion_limits(NodeClient& client) {
  fw::motion::MotionLimits m;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const std::string p = std::string(hal::kAxisNames[i]) + ".";
    m.axis[i].speed_mm_s = client.get(param((p + "path.speed_mm_s").c_str()));
    m.axis[i].accel_mm_s2 = client.get(param((p + "path.accel_mm_s2").c_str()));
    m.axis[i].jerk_mm_s3 = client.get(param((p + "path.jerk_mm_s3").c_str()));
    m.axis[i].position_min_mm = client.get(param((p + "limits.position_min_mm").c_str()));
    m.axis[i].position_max_mm = client.get(param((p + "limits.position_max_mm").c_str()));
  }
  m.path_tolerance_mm = client.get(param("path.tolerance_mm"));
  return m;
}

ProgramRunResult run_gcode(NodeClient& client, const std::string& gcode_text, const ProgramRunOptions& options) {
  const ProgramRunOptions o = with_node_tool(client, options);
  ProgramRunResult r;
  r.limits = node_motion_limits(client);
  const Heartbeat hb = client.wait_heartbeat(Micros{1'000'000});
  const std::string node = "node " + std::to_string(client.node());
  if (hb.state == fw::MotionState::faulted)
    throw RequestError(RequestError::Kind::refused, node + " is faulted (" + fw::to_string(hb.fault) +
                                                        "): `tnvctl clear-faults` first");
  if (hb.state == fw::MotionState::dwell || hb.state == fw::MotionState::moving)
    throw RequestError(RequestError::Kind::refused, node + " is moving (state " + fw::to_string(hb.state) + ")");

  PathTelemetry telemetry;
  const auto listen = [&] { client.set_listener(both(telemetry, o.on_frame)); };
  const can::ParamDef& position = param("tlm.position_ms");
  const double old_position_ms = client.get(position);
  // Sampled every tick for the score; without a score, telemetry stays as it is unless it is off
  // (the start point comes from it).
  const double run_position_ms = o.telemetry_ms > 0 ? o.telemetry_ms : (old_position_ms > 0 ? old_position_ms : 10);
  bool changed = false;
  const auto restore = [&] {
    if (!changed) return;
    changed = false;
    client.set(position, old_position_ms);
  };
  double position_now_ms = old_position_ms;
  const auto set_period = [&](double position_ms) {
    if (position_ms == position_now_ms) return;
    changed = true;
    position_now_ms = client.set(position, position_ms);
  };
  try {
    listen();
    // Where the table stands, from the telemetry as it is (on by default): a program that cannot
    // run from there is refused before anything on the node changes.
    std::optional<fw::motion::PlanePoint> start;
    if (old_position_ms > 0) {
      try {
        start = standing_reference(client, telemetry);
      } catch (const RequestError&) {
      }
    }
    if (!start) {
      set_period(run_position_ms);
      start = standing_reference(client, telemetry);
    }
    r.start_mm = *start;
    Prepared p = prepare(gcode_text, r.start_mm, r.limits, o, client.node());
    set_period(run_position_ms);
    if (hb.state == fw::MotionState::disabled) {
      client.command(can::CommandCode::enable);
      // Servo on holds where the table stood; parse again if that is not where the program was planned from.
      const fw::motion::PlanePoint held = standing_reference(client, telemetry);
      if (std::hypot(std::hypot(held[0] - r.start_mm[0], held[1] - r.start_mm[1]), held[2] - r.start_mm[2]) > 1e-6) {
        r.start_mm = held;
        p = prepare(gcode_text, r.start_mm, r.limits, o, client.node());
      }
    }
    r.program = std::move(p.program);
    r.wire = std::move(p.wire);

    telemetry = PathTelemetry{};
    StreamOptions so;
    so.window = o.window;
    so.feed_override = o.feed_override;
    so.expected_s = o.expected_s > 0.0 ? o.expected_s : r.program.programmed_time_s();
    so.interrupted = o.interrupted;
    so.progress = o.progress;
    so.before_send = o.before_send;
    so.on_pause = o.on_pause;
    so.resume = o.resume;
    so.feed_hold = o.feed_hold;
    so.on_frame = both(telemetry, o.on_frame);
    r.stream = r.program.probes == 0 ? stream_program(client, r.wire, so) : stream_probing(client, gcode_text, o, so, r);
    listen();
    client.pump(Micros{20'000});  // the reference at rest after the end closes the motion window
    client.set_listener(o.on_frame);
    try {
      restore();
    } catch (const std::exception& e) {
      r.stream.message.append(r.stream.message.empty() ? "" : "; ").append("telemetry periods not restored: ").append(e.what());
    }
  } catch (...) {
    client.set_listener(o.on_frame);
    try {
      restore();
    } catch (...) {
    }
    throw;
  }
  r.samples = telemetry.samples();
  r.telemetry_complete = !telemetry.dropped() && telemetry.unpaired() <= 1;
  if (o.telemetry_ms == 1 && r.stream.end == StreamResult::End::done)
    r.score = hil::score_path(r.program, r.samples, r.limits);
  return r;
}

}  // namespace tnv::can_host
