// tnvctl circle | move | jog | stop | estop | enable | disable |
// clear-faults | zero | home | controller | status
#include <cmath>
#include <cstdio>
#include <memory>

#include "firmware/can/param_table.hpp"
#include "hal/axis_choice.hpp"
#include "tools/can/motion_run.hpp"
#include "tools/can/node_identity.hpp"
#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

namespace {

namespace can = fw::can;
using can_host::Micros;

double seconds(Micros t) { return static_cast<double>(t.count()) * 1e-6; }
Micros micros(double s) { return Micros{static_cast<long long>(std::ceil(s * 1e6))}; }


void require_positive(const char* what, double v, double max = 1e9) {
  if (std::isfinite(v) && v > 0.0 && v <= max) return;
  char buf[128];
  std::snprintf(buf, sizeof buf, "%s must be > 0 and <= %g (got %g)", what, max, v);
  throw BadInput(buf);
}

// Waits until the heartbeat shows the motion is over; a fault is a failure.
can_host::Heartbeat finish(can_host::NodeClient& client, const std::string& what, double expected_s, Report& report) {
  const Micros started = client.bus().now();
  const can_host::Heartbeat hb = can_host::wait_motion_done(client, what, expected_s);
  const double took_s = seconds(client.bus().now() - started);
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s done after %.2f s: %s", what.c_str(), took_s, heartbeat_text(hb).c_str());
  report.line(buf);
  report.data["finished"] = true;
  report.data["wait_s"] = took_s;
  report.data["status"] = heartbeat_json(hb);
  return hb;
}

struct CircleOptions {
  std::optional<double> radius_mm;
  std::optional<double> feed_mm_s;
  bool no_wait = false;
};

void check_circle(const CircleOptions& o) {
  if (o.radius_mm) require_positive("--radius-mm", *o.radius_mm);
  if (o.feed_mm_s) require_positive("--feed-mm-s", *o.feed_mm_s);
}

int run_circle(const CircleOptions& o, Session& session, Report& report) {
  double radius_mm = 6.0;  // S1's circle when the node's scenario is unknown (real CAN)
  double feed_mm_s = 2.0;
  check_circle(o);
  can_host::NodeClient& client = session.client();
  if (const can_host::EmulatedBus* emu = session.emulated()) {
    radius_mm = emu->scenario().circle.radius_mm;
    feed_mm_s = emu->scenario().circle.feed_mm_s;
  }
  radius_mm = o.radius_mm.value_or(radius_mm);
  feed_mm_s = o.feed_mm_s.value_or(feed_mm_s);
  const can_host::CommandAck ack = client.circle(radius_mm, feed_mm_s);
  char buf[160];
  std::snprintf(buf, sizeof buf, "circle started: radius %g mm, feed %g mm/s (state %s)", radius_mm, feed_mm_s,
                fw::to_string(ack.state));
  report.line(buf);
  report.data["radius_mm"] = radius_mm;
  report.data["feed_mm_s"] = feed_mm_s;
  if (o.no_wait) return kExitOk;
  const double expected_s = can_host::circle_expected_s(client, radius_mm, feed_mm_s);
  finish(client, "circle", expected_s, report);
  return kExitOk;
}

struct MoveOptions {
  std::string axis;
  double distance_mm = 0.0;
  double speed_mm_s = 0.0;
  bool no_wait = false;
};

void check_move(const MoveOptions& o) {
  parse_axis(o.axis);
  if (!std::isfinite(o.distance_mm) || o.distance_mm == 0.0) throw BadInput("--distance-mm must be finite and not 0");
  require_positive("--speed-mm-s (the MOVE frame carries 0.01 mm/s steps)", o.speed_mm_s, 655.35);
}

int run_move(const MoveOptions& o, Session& session, Report& report) {
  check_move(o);
  const std::uint8_t axis = parse_axis(o.axis);
  can_host::NodeClient& client = session.client();
  const can_host::CommandAck ack = client.move(axis, o.distance_mm, o.speed_mm_s);
  char buf[160];
  std::snprintf(buf, sizeof buf, "move started: %s by %g mm at %g mm/s (state %s)", o.axis.c_str(), o.distance_mm,
                o.speed_mm_s, fw::to_string(ack.state));
  report.line(buf);
  if (o.no_wait) return kExitOk;
  const double expected_s = can_host::move_expected_s(client, o.distance_mm, o.speed_mm_s);
  finish(client, "move", expected_s, report);
  return kExitOk;
}

struct JogOptions {
  std::string axis;
  double speed_mm_s = 0.0;
  double duration_s = 1.0;
  int period_ms = 0;  // 0: half the axis' jog.deadman_s, at most 50 ms
};

void check_jog(const JogOptions& o) {
  parse_axis(o.axis);
  if (!std::isfinite(o.speed_mm_s)) throw BadInput("--speed-mm-s must be finite");
  require_positive("--duration-s", o.duration_s, 3600);
}

int run_jog(const JogOptions& o, Session& session, Report& report) {
  check_jog(o);
  const std::uint8_t axis = parse_axis(o.axis);
  can_host::NodeClient& client = session.client();
  const std::string prefix = o.axis + ".jog.";
  const double deadman_s = client.get(*can::find_param((prefix + "deadman_s").c_str()));
  const double accel = client.get(*can::find_param((prefix + "accel_mm_s2").c_str()));
  double period_s = o.period_ms > 0 ? o.period_ms * 1e-3 : std::min(0.05, deadman_s / 2.0);
  if (period_s >= deadman_s) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "--period-ms %d is not shorter than %s.jog.deadman_s (%g s)", o.period_ms,
                  o.axis.c_str(), deadman_s);
    throw BadInput(buf);
  }
  const Micros start = client.bus().now();
  const Micros end = start + micros(o.duration_s);
  int frames = 0;
  for (Micros next = start; client.bus().now() < end; next += micros(period_s)) {
    client.jog(axis, o.speed_mm_s);
    ++frames;
    const Micros wait = std::min(next + micros(period_s), end) - client.bus().now();
    if (wait > Micros{0}) client.pump(wait);
  }
  client.jog(axis, 0.0);
  ++frames;
  char buf[160];
  std::snprintf(buf, sizeof buf, "jog %s at %g mm/s for %g s: %d JOG frames, one every %.0f ms", o.axis.c_str(),
                o.speed_mm_s, o.duration_s, frames, period_s * 1e3);
  report.line(buf);
  report.data["frames"] = frames;
  report.data["period_ms"] = period_s * 1e3;
  finish(client, "jog", std::fabs(o.speed_mm_s) / std::max(accel, 1e-9), report);
  return kExitOk;
}

void report_ack(can::CommandCode code, const can_host::CommandAck& ack, Report& report) {
  std::string text = can::to_string(code);
  text.append(": ok (state ").append(fw::to_string(ack.state)).append(", fault ").append(fw::to_string(ack.fault)).append(")");
  report.line(text);
  report.data["state"] = fw::to_string(ack.state);
  report.data["fault"] = fw::to_string(ack.fault);
}

int run_simple_command(can::CommandCode code, Session& session, Report& report) {
  report_ack(code, session.client().command(code), report);
  return kExitOk;
}

// A board trip (watchdog, encoder or DAC latch) takes two clears
// (can_host::clear_faults sends the second); a cause that is still there
// after it (an e-stop held, a limit switch pressed) is the node's refusal,
// reported as it is.
int run_clear_faults(Session& session, Report& report) {
  bool retried = false;
  const can_host::CommandAck ack = can_host::clear_faults(session.client(), retried);
  if (retried) {
    report.line("clear_faults: cause_present (a board latch is reset by the first clear); sent again 5 ms later");
    report.data["retried"] = true;
  }
  report_ack(can::CommandCode::clear_faults, ack, report);
  return kExitOk;
}

int run_stop(bool no_wait, Session& session, Report& report) {
  run_simple_command(can::CommandCode::stop, session, report);
  if (!no_wait) finish(session.client(), "stop", 10.0, report);
  return kExitOk;
}

int run_estop(bool all, Session& session, Report& report) {
  can_host::NodeClient& client = session.client();
  client.estop(all);
  // Never acknowledged: the heartbeat shows it.
  const Micros deadline = client.bus().now() + std::max(client.options().timeout, Micros{1'000'000});
  for (;;) {
    const Micros left = deadline - client.bus().now();
    if (left <= Micros{0}) throw RunFailed("no HEARTBEAT showed the e-stop within 1 s (is tlm.heartbeat_ms 0?)");
    const can_host::Heartbeat hb = client.wait_heartbeat(left);
    if (hb.state == fw::MotionState::faulted) {
      std::string text = all ? "e-stop sent to every node (node 0)" : "e-stop sent";
      report.line(text.append(": ").append(heartbeat_text(hb)));
      report.data["status"] = heartbeat_json(hb);
      return kExitOk;
    }
  }
}

int run_zero(const std::string& axis_name, double position_mm, Session& session, Report& report) {
  const std::uint8_t axis = parse_axis(axis_name);
  if (!std::isfinite(position_mm)) throw BadInput("--position must be finite");
  session.client().command(can::CommandCode::zero, axis, 0, position_mm);
  char buf[96];
  std::snprintf(buf, sizeof buf, "axis %s now reads %g mm", axis_name.c_str(), position_mm);
  report.line(buf);
  return kExitOk;
}

// COMMAND home, then wait for rest: the cycle's own bounds (search and
// latch travels at their speeds) give the longest it can take.
int run_home(const std::string& axis_name, Session& session, Report& report) {
  const bool all = axis_name == "all";
  const std::uint8_t axis = all ? 255 : parse_axis(axis_name);
  can_host::NodeClient& client = session.client();
  const double bound_s = can_host::homing_bound_s(client, axis);
  client.command(can::CommandCode::home, axis);
  const can_host::Heartbeat hb = finish(client, "home " + axis_name, bound_s, report);
  report.data["homed"] = nlohmann::json::object();
  for (const hal::Axis a : hal::kAxes)
    report.data["homed"][hal::axis_label(a)] = hb.homed(a);
  if (const auto why = can_host::not_homed_message(hb, axis)) throw RunFailed(*why);
  return kExitOk;
}

int run_controller(const std::string& axis_name, const std::string& kind, Session& session, Report& report) {
  const std::uint8_t axis = axis_name == "all" ? 255 : parse_axis(axis_name);
  const std::uint8_t arg = kind == "pid" ? 0 : kind == "dvsc" ? 1 : 2;
  session.client().command(can::CommandCode::select_controller, axis, arg);
  std::string text = "controller of ";
  report.line(text.append(axis_name).append(": ").append(kind));
  report.data["controller"] = kind;
  return kExitOk;
}

int run_status(Session& session, Report& report) {
  can_host::NodeClient& client = session.client();
  const can_host::Heartbeat hb = client.wait_heartbeat(std::max(client.options().timeout, Micros{1'000'000}));
  const can_host::CaptureStatus cap = client.capture(can::CaptureOp::status);
  const can_host::NodeIdentity id = can_host::read_identity(client);
  const char* states[] = {"idle", "armed", "recording", "done"};
  std::string text = "node ";
  text.append(std::to_string(client.node())).append(" (firmware ").append(can_host::firmware_version_text(id.firmware_version));
  text.append(", build ").append(can_host::build_id_text(id.build_id)).append(") on ");
  text.append(client.bus().describe()).append(": ");
  text.append(heartbeat_text(hb)).append("; capture ").append(states[static_cast<int>(cap.state) & 3]);
  text.append(" (").append(std::to_string(cap.samples)).append(" samples)");
  report.line(text);
  report.data["status"] = heartbeat_json(hb);
  report.data["capture"] = {{"state", states[static_cast<int>(cap.state) & 3]}, {"samples", cap.samples}};
  report.data["firmware"] = firmware_json(id);
  return kExitOk;
}

}  // namespace

void add_motion_commands(CLI::App& app, ActionSlot& slot) {
  auto circle = std::make_shared<CircleOptions>();
  CLI::App* circle_cmd =
      app.add_subcommand("circle", "run the S1 circle from where the table stands; waits until it is done");
  circle_cmd->add_option("--radius-mm", circle->radius_mm, "mm (default: the emulated scenario's, else 6)");
  circle_cmd->add_option("--feed-mm-s", circle->feed_mm_s, "mm/s (default: the emulated scenario's, else 2)");
  circle_cmd->add_flag("--no-wait", circle->no_wait, "return once the node accepted it");
  circle_cmd->callback([&slot, circle] {
    slot = Action{"circle", true, [circle](Session& s, Report& r) { return run_circle(*circle, s, r); },
                  [circle] { check_circle(*circle); }};
  });

  auto move = std::make_shared<MoveOptions>();
  CLI::App* move_cmd = app.add_subcommand("move", "point-to-point move of one axis; waits until it is done");
  move_cmd->add_option("--axis", move->axis, hal::kAxisChoices)->required()
      ->check(CLI::IsMember(std::vector<std::string>(hal::kAxisNames.begin(), hal::kAxisNames.end())));
  move_cmd->add_option("--distance-mm", move->distance_mm, "signed distance, mm")->required();
  move_cmd->add_option("--speed-mm-s", move->speed_mm_s, "cruise speed, mm/s")->required();
  move_cmd->add_flag("--no-wait", move->no_wait, "return once the node accepted it");
  move_cmd->callback([&slot, move] {
    slot = Action{"move", true, [move](Session& s, Report& r) { return run_move(*move, s, r); },
                  [move] { check_move(*move); }};
  });

  auto jog = std::make_shared<JogOptions>();
  CLI::App* jog_cmd = app.add_subcommand("jog", "stream JOG frames (a held pendant key), then stop");
  jog_cmd->add_option("--axis", jog->axis, hal::kAxisChoices)->required()
      ->check(CLI::IsMember(std::vector<std::string>(hal::kAxisNames.begin(), hal::kAxisNames.end())));
  jog_cmd->add_option("--speed-mm-s", jog->speed_mm_s, "signed target speed, mm/s")->required();
  jog_cmd->add_option("--duration-s", jog->duration_s, "seconds to keep streaming")->capture_default_str();
  jog_cmd->add_option("--period-ms", jog->period_ms, "JOG frame period (default: half of jog.deadman_s, <= 50 ms)")
      ->check(CLI::Range(1, 10000));
  jog_cmd->callback([&slot, jog] {
    slot = Action{"jog", true, [jog](Session& s, Report& r) { return run_jog(*jog, s, r); }, [jog] { check_jog(*jog); }};
  });

  auto stop_no_wait = std::make_shared<bool>(false);
  CLI::App* stop_cmd = app.add_subcommand("stop", "controlled stop along the path, then hold");
  stop_cmd->add_flag("--no-wait", *stop_no_wait, "return once the node accepted it");
  stop_cmd->callback([&slot, stop_no_wait] {
    slot = Action{"stop", true, [stop_no_wait](Session& s, Report& r) { return run_stop(*stop_no_wait, s, r); }};
  });

  auto estop_all = std::make_shared<bool>(false);
  CLI::App* estop_cmd = app.add_subcommand("estop", "emergency stop: outputs safe, fault latched");
  estop_cmd->add_flag("--all", *estop_all, "send to node 0: every node on the bus");
  estop_cmd->callback([&slot, estop_all] {
    slot = Action{"estop", true, [estop_all](Session& s, Report& r) { return run_estop(*estop_all, s, r); }};
  });

  const std::pair<const char*, can::CommandCode> simple[] = {
      {"enable", can::CommandCode::enable},
      {"disable", can::CommandCode::disable},
  };
  const char* simple_help[] = {"servo on, hold where the table stands", "servo off (DACs mid-scale)"};
  for (std::size_t i = 0; i < std::size(simple); ++i) {
    const auto [name, code] = simple[i];
    app.add_subcommand(name, simple_help[i])->callback([&slot, name = std::string(name), code = code] {
      slot = Action{name, true, [code](Session& s, Report& r) { return run_simple_command(code, s, r); }};
    });
  }

  app.add_subcommand("clear-faults",
                     "unlatch the fault if its cause is gone (a board trip takes two clears: sent again once, "
                     "5 ms later)")
      ->callback([&slot] {
        slot = Action{"clear-faults", true, [](Session& s, Report& r) { return run_clear_faults(s, r); }};
      });

  auto zero_axis = std::make_shared<std::string>();
  auto zero_position = std::make_shared<double>(0.0);
  CLI::App* zero_cmd = app.add_subcommand("zero", "assign a position to an axis at rest");
  zero_cmd->add_option("--axis", *zero_axis, hal::kAxisChoices)->required()
      ->check(CLI::IsMember(std::vector<std::string>(hal::kAxisNames.begin(), hal::kAxisNames.end())));
  zero_cmd->add_option("--position", *zero_position, "mm")->capture_default_str();
  zero_cmd->callback([&slot, zero_axis, zero_position] {
    slot = Action{"zero", true,
                  [zero_axis, zero_position](Session& s, Report& r) { return run_zero(*zero_axis, *zero_position, s, r); }};
  });

  auto ctl_axis = std::make_shared<std::string>("all");
  auto ctl_kind = std::make_shared<std::string>();
  auto home_axis = std::make_shared<std::string>("all");
  CLI::App* home_cmd = app.add_subcommand(
      "home", "homing cycle: search the home switch, back off, latch the next index; waits until homed");
  std::string homing_order;  // "x then y"
  for (const hal::Axis a : hal::kHomingOrder)
    homing_order.append(homing_order.empty() ? "" : " then ").append(hal::axis_label(a));
  home_cmd->add_option("--axis", *home_axis, axis_help_or("all") + " (" + homing_order + ")")
      ->capture_default_str()
      ->check(CLI::IsMember(axis_values_or("all")));
  home_cmd->callback([&slot, home_axis] {
    slot = Action{"home", true, [home_axis](Session& s, Report& r) { return run_home(*home_axis, s, r); }};
  });

  CLI::App* ctl_cmd = app.add_subcommand("controller", "select the axis loop (at rest)");
  ctl_cmd->add_option("--axis", *ctl_axis, axis_help_or("all"))
      ->check(CLI::IsMember(axis_values_or("all")))
      ->capture_default_str();
  ctl_cmd->add_option("--controller", *ctl_kind, "pid | dvsc | rdvsc")->required()->check(CLI::IsMember({"pid", "dvsc", "rdvsc"}));
  ctl_cmd->callback([&slot, ctl_axis, ctl_kind] {
    slot = Action{"controller", true,
                  [ctl_axis, ctl_kind](Session& s, Report& r) { return run_controller(*ctl_axis, *ctl_kind, s, r); }};
  });

  app.add_subcommand("status", "one heartbeat: state, fault, flags; capture state")->callback([&slot] {
    slot = Action{"status", true, [](Session& s, Report& r) { return run_status(s, r); }};
  });
}

}  // namespace tnv::tnvctl
