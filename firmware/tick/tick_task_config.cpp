// TickTask::apply_config(): a whole new config from the CAN node, applied
// whole or not at all.
#include "firmware/tick/tick_task.hpp"

namespace tnv::fw {

// --- commands for the CAN node

namespace {

// `to` with what apply_config() takes while moving (or never applies) set
// back to `from`'s: equal to `from` exactly when nothing else differs. Each
// part is compared by its operator== (member by member), so a field added
// to a part is not live unless it is named here.
FirmwareConfig without_live_changes(const FirmwareConfig& from, const FirmwareConfig& to) noexcept {
  FirmwareConfig c = to;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    AxisConfig& a = c.axis[i];
    const AxisConfig& f = from.axis[i];
    a.home_position_mm = f.home_position_mm;  // never applied: zero() moves the frame
    a.sliding = f.sliding;                    // sliding.*: all live
    // PID: kp, ki, kd and the clamp are live; the filter and the feed-forward switch are not.
    a.pid.kp = f.pid.kp;
    a.pid.ki = f.pid.ki;
    a.pid.kd = f.pid.kd;
    a.pid.u_max_mm_s = f.pid.u_max_mm_s;
  }
  // The tick's timing: no parameter, the CAN node keeps the running values.
  c.supervisor.tick_period_clocks = from.supervisor.tick_period_clocks;
  c.supervisor.period_tolerance_clocks = from.supervisor.period_tolerance_clocks;
  // The force loop: f* and the sensor scale are live, the rest waits for rest (a new loop).
  c.force_sensor = from.force_sensor;
  c.arsc.force_ref_n = from.arsc.force_ref_n;
  return c;
}

// Everything of the force loop but f* (which it takes on line).
bool same_but_force_ref(const arsc::ArscSourceParams& a, const arsc::ArscSourceParams& b) noexcept {
  arsc::ArscSourceParams b_with_a_ref = b;
  b_with_a_ref.force_ref_n = a.force_ref_n;
  return a == b_with_a_ref;
}

}  // namespace

bool TickTask::live_tunable_only(const FirmwareConfig& from, const FirmwareConfig& to) noexcept {
  return without_live_changes(from, to) == from;
}

CommandStatus TickTask::apply_config(const FirmwareConfig& config) noexcept {
  // After the first accepted config, only what differs from the running one is checked again.
  if (!(config_validated_ ? validate(config, config_) : validate(config)).ok()) return CommandStatus::invalid;
  if (moving() && !live_tunable_only(config_, config)) return CommandStatus::busy;
  const bool spindle_changed = !(config.spindle == config_.spindle);
  if (spindle_changed && !spindle_.can_set_params()) return CommandStatus::spindle_running;
  // Everything checked: from here on nothing can refuse, so it applies whole.
  FirmwareConfig next = config;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    AxisConfig& a = next.axis[i];
    const AxisConfig& old = config_.axis[i];
    a.home_position_mm = old.home_position_mm;  // the frame moves with zero() only
    axis_[i].apply(old, a, servo_on(), record_.axis[i].position_mm);
    if (a.count_mm != old.count_mm) {
      // Re-base: the position reading stays where it is, later counts use the new scale.
      const double counts = static_cast<double>(axis_[i].counts());
      origin_mm_[i] = origin_mm_[i] + counts * old.count_mm - counts * a.count_mm;
    }
  }
  // The planner's limits (the soft limits are the supervisor's): at rest only (moving: busy above).
  bool path_changed = next.path_tolerance_mm != config_.path_tolerance_mm;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    path_changed = path_changed || next.axis[i].path != config_.axis[i].path ||
                   next.supervisor.axis[i].position_min_mm != config_.supervisor.axis[i].position_min_mm ||
                   next.supervisor.axis[i].position_max_mm != config_.supervisor.axis[i].position_max_mm;
  // The force loop: a new loop at rest (validated with the config), f* on line.
  if (!same_but_force_ref(next.arsc, config_.arsc)) feed_.configure(next.arsc);
  else if (next.arsc.force_ref_n != config_.arsc.force_ref_n) feed_.set_force_ref_n(next.arsc.force_ref_n);
  if (spindle_changed) (void)spindle_.set_params(next.spindle);  // stopped and still, validated: cannot refuse
  config_ = next;
  config_validated_ = true;
  if (path_changed) (void)motion_.configure(path_limits(config_), held_point());  // validated with the config
  return CommandStatus::ok;
}

}  // namespace tnv::fw
