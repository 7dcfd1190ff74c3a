#include "tools/serve/page_program.hpp"

#include <openssl/evp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "tools/serve/api_error.hpp"
#include "tools/serve/http_reply.hpp"

namespace tnv::serve {

namespace {

double rounded(double v) { return std::round(v * 1e4) / 1e4; }  // 0.1 um: finer than any screen

// The points of one segment after its start: arcs in chords of at most kPreviewArcStepRad.
std::size_t chords(const fw::motion::SegmentGeometry& g) {
  if (g.kind != fw::motion::SegmentKind::arc_cw && g.kind != fw::motion::SegmentKind::arc_ccw) return 1;
  const double n = std::ceil(std::fabs(g.sweep_rad) / kPreviewArcStepRad);
  return static_cast<std::size_t>(std::clamp(n, 1.0, 4096.0));
}

// body[key] as a whole number in [min, max]; `fallback` when absent.
long whole_field(const nlohmann::json& body, const char* key, long fallback, long min, long max) {
  if (!body.contains(key)) return fallback;
  const nlohmann::json& v = body[key];
  if (!v.is_number_integer() || v.get<long long>() < min || v.get<long long>() > max)
    throw ApiError(kHttpBadRequest, std::string(key) + " must be a whole number from " + std::to_string(min) + " to " +
                                        std::to_string(max) + " (got " + v.dump() + ")");
  return static_cast<long>(v.get<long long>());
}

// body[key] as a finite number of at least `min`; `fallback` when absent.
double number_field(const nlohmann::json& body, const char* key, double fallback, double min) {
  if (!body.contains(key)) return fallback;
  const nlohmann::json& v = body[key];
  if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < min)
    throw ApiError(kHttpBadRequest, std::string(key) + " must be a number" +
                                        (std::isfinite(min) ? " >= " + std::to_string(static_cast<long>(min)) : "") +
                                        " (got " + v.dump() + ")");
  return v.get<double>();
}

// body[key] as true or false; `fallback` when absent.
bool switch_field(const nlohmann::json& body, const char* key, bool fallback) {
  if (!body.contains(key)) return fallback;
  if (!body[key].is_boolean())
    throw ApiError(kHttpBadRequest, std::string(key) + " must be true or false (got " + body[key].dump() + ")");
  return body[key].get<bool>();
}

}  // namespace

gcode::CanonSetup page_canon_setup(const nlohmann::json& body) {
  gcode::CanonSetup setup;
  // The operator's switches, LinuxCNC's defaults (on) when absent: --optional-stop and --block-delete.
  setup.optional_stop = switch_field(body, "optional_stop", setup.optional_stop);
  setup.block_delete = switch_field(body, "block_delete", setup.block_delete);
  // The tool table and parameter file as their texts (the page reads the files), as --tool-table and
  // --var-file load them: LinuxCNC's .tbl (lengths in mm) and .var (work offsets, G28/G30, G92 in mm).
  std::string error;
  if (body.contains("tool_table") && !setup.tools.load_text(text_field(body, "tool_table"), error))
    throw ApiError(kHttpBadRequest, "tool_table: " + error);
  if (body.contains("var_file") && !setup.parameters.load_var_text(text_field(body, "var_file"), error))
    throw ApiError(kHttpBadRequest, "var_file: " + error);
  const char* companions[] = {"from_pass", "tool_in_spindle", "approach_height_mm", "clearance_z_mm"};
  if (!body.contains("from_line")) {
    for (const char* key : companions)
      if (body.contains(key)) throw ApiError(kHttpBadRequest, std::string(key) + " needs from_line");
    return setup;
  }
  constexpr long kMax = std::numeric_limits<int>::max();
  gcode::RunFromLine from;
  from.line = static_cast<int>(whole_field(body, "from_line", 0, 1, kMax));
  from.pass = whole_field(body, "from_pass", from.pass, 1, kMax);
  from.tool_in_spindle = static_cast<int>(whole_field(body, "tool_in_spindle", from.tool_in_spindle, 0, kMax));
  from.approach_mm = number_field(body, "approach_height_mm", from.approach_mm, 0.0);
  from.clearance_z_mm = number_field(body, "clearance_z_mm", from.clearance_z_mm, -HUGE_VAL);
  setup.from_line = from;
  return setup;
}

nlohmann::json program_summary(const std::string& gcode_text) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  std::string hex;
  if (EVP_Digest(gcode_text.data(), gcode_text.size(), digest, &size, EVP_sha256(), nullptr) == 1) {
    char buf[3];
    for (unsigned int i = 0; i < size; ++i) {
      std::snprintf(buf, sizeof buf, "%02x", digest[i]);
      hex += buf;
    }
  }
  std::size_t lines = static_cast<std::size_t>(std::count(gcode_text.begin(), gcode_text.end(), '\n'));
  if (!gcode_text.empty() && gcode_text.back() != '\n') ++lines;
  return {{"bytes", gcode_text.size()}, {"lines", lines}, {"sha256", hex}};
}

nlohmann::json plan_refusal(const can_host::ProgramPlan& plan) {
  if (plan.parsed.error) {
    const gcode::GcodeError& e = *plan.parsed.error;
    return {{"error", gcode::to_string(e)}, {"line", e.line}, {"column", e.column}};
  }
  if (plan.parsed.program.segments.empty()) return {{"error", "the program has no motion and no dwell"}};
  if (!plan.wire_error.empty()) return {{"error", plan.wire_error}};
  return nullptr;
}

nlohmann::json preview_json(const can_host::ProgramPlan& plan, std::size_t max_points) {
  const gcode::GcodeProgram& p = plan.parsed.program;
  std::size_t total = 0;
  for (const fw::motion::SegmentGeometry& g : p.geometry)
    if (g.length_mm > 0.0) total += 1 + chords(g);
  // Past the budget, `group` consecutive segments share a piece and every `stride`-th point is kept:
  // about total / stride points plus two ends per piece, within max_points.
  const std::size_t budget = std::max<std::size_t>(max_points, 16);
  const std::size_t stride = total <= budget ? 1 : (3 * total + budget - 1) / budget;
  const std::size_t group = stride;

  nlohmann::json pieces = nlohmann::json::array();
  std::vector<double> points;
  int first_line = 0;
  int last_line = 0;
  std::size_t in_group = 0;
  std::size_t counter = 0;
  std::size_t drawn = 0;
  const auto flush = [&] {
    if (points.size() >= 4) {
      drawn += points.size() / 2;
      pieces.push_back({{"line", first_line}, {"last_line", last_line}, {"points", points}});
    }
    points.clear();
    in_group = 0;
  };
  const auto add = [&](const fw::motion::PlanePoint& q, bool keep) {
    if (keep || counter % stride == 0) {
      points.push_back(rounded(q[0]));
      points.push_back(rounded(q[1]));
    }
    ++counter;
  };
  for (std::size_t i = 0; i < p.geometry.size(); ++i) {
    const fw::motion::SegmentGeometry& g = p.geometry[i];
    if (g.length_mm <= 0.0) continue;  // a dwell
    const int line = static_cast<int>(p.segments[i].tag);
    if (in_group == 0) {
      first_line = line;
      add(g.start_mm, true);
    }
    last_line = line;
    const std::size_t n = chords(g);
    for (std::size_t k = 1; k <= n; ++k) add(g.point_at(g.length_mm * static_cast<double>(k) / static_cast<double>(n)), k == n && in_group + 1 == group);
    if (++in_group == group) flush();
  }
  if (!points.empty()) {
    // The last piece ends where its last segment does.
    const fw::motion::SegmentGeometry* last = nullptr;
    for (const fw::motion::SegmentGeometry& g : p.geometry)
      if (g.length_mm > 0.0) last = &g;
    if (last != nullptr && (points[points.size() - 2] != rounded(last->end_mm[0]) ||
                            points.back() != rounded(last->end_mm[1]))) {
      points.push_back(rounded(last->end_mm[0]));
      points.push_back(rounded(last->end_mm[1]));
    }
    flush();
  }
  const fw::motion::MotionLimits& l = plan.limits;
  nlohmann::json out = {{"lines", p.lines_run},
                        {"segments", p.segments.size()},
                        {"cycle_time_s", p.programmed_time_s()},
                        {"length_mm", p.programmed_length_mm()},
                        {"tool_changes", p.tool_changes},
                        {"summary", gcode::summary_text(p)},
                        {"start", {plan.start_mm[0], plan.start_mm[1]}},
                        {"travel",
                         {{"x", {l.axis[0].position_min_mm, l.axis[0].position_max_mm}},
                          {"y", {l.axis[1].position_min_mm, l.axis[1].position_max_mm}}}},
                        {"pieces", std::move(pieces)},
                        {"points", drawn},
                        {"thinned", stride > 1},
                        {"note", ""}};
  if (stride > 1) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "the path has %zu points: drawn with %zu (every %zu-th, %zu segments a piece)", total,
                  drawn, stride, group);
    out["note"] = buf;
  }
  return out;
}

nlohmann::json run_program_for_page(can_host::NodeClient& client, const std::string& gcode_text,
                                    const gcode::CanonSetup& canon, bool tool_from_node, ProgramState& state,
                                    const can_host::FrameListener& scope) {
  can_host::ProgramRunOptions o;
  o.canon = canon;
  o.tool_from_node = tool_from_node;
  o.telemetry_ms = 0;
  o.on_frame = scope;
  // Called on this (the node) thread between the stream's bus operations, so
  // the e-stop goes out from here at once, not after the braking and the
  // program's end as a job queued behind this one would.
  o.interrupted = [&state, &client, estop_sent = false]() mutable {
    if (state.estop_requested() && !estop_sent) {
      client.estop(false);
      estop_sent = true;
    }
    return state.interrupted();
  };
  o.progress = [&state](const can_host::StreamProgress& p) { state.progress(p); };
  // A pause waits for the Resume button of the tab with control (POST /api/program/resume).
  o.on_pause = [&state](const can_host::StreamPause& p) { state.paused(p); };
  o.resume = [&state](const can_host::StreamPause&, can_host::Micros) { return state.take_resume(); };
  // The Feed hold button (POST /api/program/hold): brakes on the path and waits there until released.
  o.feed_hold = [&state] { return state.feed_hold_wanted(); };
  bool started = false;
  o.before_send = [&](std::size_t) {
    if (started) return;
    started = true;
    state.streaming();
  };
  can_host::ProgramRunResult r;
  try {
    // Planned first: a refusal names its line and column as the preview's does.
    const can_host::ProgramPlan plan = can_host::plan_gcode(client, gcode_text, o);
    if (nlohmann::json refusal = plan_refusal(plan); !refusal.is_null()) {
      const std::string why = refusal["error"].get<std::string>();
      throw ApiError(kHttpBadRequest, why, std::move(refusal));
    }
    if (state.interrupted()) throw ApiError(kHttpConflict, "stopped before it started");
    r = can_host::run_gcode(client, gcode_text, o);
  } catch (const can_host::ProgramInputError& e) {
    state.finish("refused", e.what());
    throw ApiError(kHttpBadRequest, e.what());
  } catch (const ApiError& e) {
    state.finish("refused", e.what());
    throw;
  } catch (const std::exception& e) {
    state.finish(started ? "failed" : "refused", e.what());
    throw;
  }
  using End = can_host::StreamResult::End;
  const std::string end = r.stream.end == End::done ? "done" : r.stream.end == End::interrupted ? "interrupted" : "failed";
  state.finish(end, r.stream.message);
  return {{"end", end},
          {"message", r.stream.message},
          {"summary", gcode::summary_text(r.program)},
          {"elements", r.wire.elements.size()},
          {"run_s", r.stream.run_s},
          {"underruns", r.stream.underruns}};
}

}  // namespace tnv::serve
