// tnvctl spindle start --rpm N [--reverse] | stop | speed N: the SPINDLE
// request (docs/safety.md "Spindle"). Each returns once the node answered:
// the spindle ramps on its own, and feed moves wait until it is at speed.
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "tools/can/spindle_command.hpp"
#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

namespace {

namespace can = fw::can;

struct SpindleOptions {
  can::SpindleOp op = can::SpindleOp::stop;
  double rpm = 0.0;
  bool reverse = false;
};

void check_spindle(const SpindleOptions& o) {
  try {
    can_host::check_spindle_rpm(o.op, o.rpm);
  } catch (const std::invalid_argument& e) {
    throw BadInput(e.what());
  }
}

int run_spindle(const SpindleOptions& o, Session& session, Report& report) {
  check_spindle(o);
  const fw::SpindleDirection direction = o.reverse ? fw::SpindleDirection::reverse : fw::SpindleDirection::forward;
  const can_host::CommandAck ack = can_host::spindle_command(session.client(), o.op, direction, o.rpm);
  char buf[160];
  if (o.op == can::SpindleOp::start)
    std::snprintf(buf, sizeof buf, "spindle started: %s at %g rpm (state %s)", fw::to_string(direction), o.rpm,
                  fw::to_string(ack.state));
  else if (o.op == can::SpindleOp::speed)
    std::snprintf(buf, sizeof buf, "spindle speed: %g rpm (state %s)", o.rpm, fw::to_string(ack.state));
  else
    std::snprintf(buf, sizeof buf, "spindle stopping (state %s)", fw::to_string(ack.state));
  report.line(buf);
  report.data["op"] = can::to_string(o.op);
  if (o.op != can::SpindleOp::stop) report.data["rpm"] = o.rpm;
  if (o.op == can::SpindleOp::start) report.data["direction"] = fw::to_string(direction);
  report.data["state"] = fw::to_string(ack.state);
  return kExitOk;
}

}  // namespace

void add_spindle_commands(CLI::App& app, ActionSlot& slot) {
  CLI::App* spindle = app.add_subcommand("spindle", "start, stop or change the spindle's speed (needs ownership)");
  spindle->require_subcommand(1);
  const auto action = [&slot](const std::shared_ptr<SpindleOptions>& o) {
    slot = Action{"spindle", true, [o](Session& s, Report& r) { return run_spindle(*o, s, r); },
                  [o] { check_spindle(*o); }};
  };

  auto start = std::make_shared<SpindleOptions>();
  start->op = can::SpindleOp::start;
  CLI::App* start_cmd = spindle->add_subcommand("start", "turn at --rpm (M3; --reverse: M4); feed moves wait for it");
  start_cmd->add_option("--rpm", start->rpm, "speed, rpm (at most spindle.max_rpm)")->required();
  start_cmd->add_flag("--reverse", start->reverse, "counter-clockwise (M4)");
  start_cmd->callback([action, start] { action(start); });

  auto stop = std::make_shared<SpindleOptions>();
  CLI::App* stop_cmd = spindle->add_subcommand("stop", "ramp down and drop the enable at standstill (M5)");
  stop_cmd->callback([action, stop] { action(stop); });

  auto speed = std::make_shared<SpindleOptions>();
  speed->op = can::SpindleOp::speed;
  CLI::App* speed_cmd = spindle->add_subcommand("speed", "a new speed while it turns; feed moves wait for it");
  speed_cmd->add_option("rpm", speed->rpm, "speed, rpm")->required();
  speed_cmd->callback([action, speed] { action(speed); });
}

}  // namespace tnv::tnvctl
