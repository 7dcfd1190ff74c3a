#include "tools/can/motion_run.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "firmware/can/param_table.hpp"

namespace tnv::can_host {

namespace {

double node_param(NodeClient& client, const std::string& name) { return client.get(*fw::can::find_param(name.c_str())); }

}  // namespace

double move_expected_s(NodeClient& client, double distance_mm, double speed_mm_s) {
  return node_param(client, "motion.move_dwell_s") + 2.0 * node_param(client, "motion.move_ramp_s") +
         std::fabs(distance_mm) / speed_mm_s;
}

double circle_expected_s(NodeClient& client, double radius_mm, double feed_mm_s) {
  return node_param(client, "motion.circle_dwell_s") + node_param(client, "motion.circle_ramp_s") +
         2.0 * std::numbers::pi * radius_mm / feed_mm_s;
}

double homing_bound_s(NodeClient& client, std::uint8_t axis) {
  double bound_s = 0.0;
  for (const hal::Axis a : hal::kAxes) {
    if (axis != kAllAxes && axis != hal::index(a)) continue;
    const std::string p = std::string(hal::axis_label(a)) + ".homing.";
    bound_s += node_param(client, p + "search_max_mm") / node_param(client, p + "search_mm_s") +
               2.0 * node_param(client, p + "latch_max_mm") / node_param(client, p + "latch_mm_s") + 1.0;
  }
  return bound_s;
}

std::optional<std::string> not_homed_message(const Heartbeat& hb, std::uint8_t axis) {
  for (const hal::Axis a : hal::kAxes)
    if ((axis == kAllAxes || axis == hal::index(a)) && !hb.homed(a))
      return std::string(hal::axis_label(a)) + " is not homed (the cycle was stopped?)";
  return std::nullopt;
}

std::optional<std::string> fault_message(const Heartbeat& hb, NodeClient& client, const std::string& what) {
  if (hb.state != fw::MotionState::faulted) return std::nullopt;
  std::string message = what;
  message.append(" ended in a fault: ").append(fw::to_string(hb.fault));
  if (const auto& ev = client.last_fault_event(); ev && ev->reason == hb.fault) {
    if (ev->axis >= 0 && static_cast<std::size_t>(ev->axis) < hal::kAxisCount)
      message.append(" on axis ").append(hal::kAxisNames[static_cast<std::size_t>(ev->axis)]);
    char buf[64];
    std::snprintf(buf, sizeof buf, " (value %g, tick ...%u)", ev->value, static_cast<unsigned>(ev->tick_low));
    message += buf;
  }
  message += "; `tnvctl clear-faults` unlatches it";
  return message;
}

Heartbeat wait_motion_done(NodeClient& client, const std::string& what, double expected_s) {
  const Heartbeat hb = client.wait_at_rest(Micros{static_cast<long long>(std::ceil((expected_s * 1.5 + 5.0) * 1e6))});
  if (const auto fault = fault_message(hb, client, what)) throw MotionFailed(*fault);
  return hb;
}

CommandAck clear_faults(NodeClient& client, bool& retried) {
  retried = false;
  try {
    return client.command(fw::can::CommandCode::clear_faults);
  } catch (const RequestError& e) {
    if (e.kind() != RequestError::Kind::refused || e.code() != fw::can::ErrorCode::cause_present) throw;
  }
  client.pump(Micros{5'000});
  retried = true;
  return client.command(fw::can::CommandCode::clear_faults);
}

}  // namespace tnv::can_host
