// TickTask::apply_config(): a whole new config from the CAN node, applied
// whole or not at all.
#include "firmware/tick/tick_task.hpp"

namespace tnv::fw {

// --- commands for the CAN node

namespace {

bool same(const AxisModel& a, const AxisModel& b) noexcept {
  return a.A == b.A && a.B == b.B && a.period_s == b.period_s;
}
bool same(const SlidingModeParams& a, const SlidingModeParams& b) noexcept {
  return a.G_position_1_s == b.G_position_1_s && a.G_speed == b.G_speed && a.eta_mm_s == b.eta_mm_s &&
         a.phi_mm_s == b.phi_mm_s && a.q == b.q && a.g == b.g && a.gamma == b.gamma && a.u_max_mm_s == b.u_max_mm_s;
}
bool same(const PidParams& a, const PidParams& b) noexcept {
  return a.kp == b.kp && a.ki == b.ki && a.kd == b.kd && a.derivative_filter_tf_s == b.derivative_filter_tf_s &&
         a.u_max_mm_s == b.u_max_mm_s && a.feedforward == b.feedforward;
}
bool same(const PathLimits& a, const PathLimits& b) noexcept {
  return a.speed_mm_s == b.speed_mm_s && a.accel_mm_s2 == b.accel_mm_s2 && a.jerk_mm_s3 == b.jerk_mm_s3;
}
bool same(const JogLimits& a, const JogLimits& b) noexcept {
  return a.speed_max_mm_s == b.speed_max_mm_s && a.accel_mm_s2 == b.accel_mm_s2 && a.deadman_s == b.deadman_s;
}
bool same(const HomingParams& a, const HomingParams& b) noexcept {
  return a.search_positive == b.search_positive && a.search_mm_s == b.search_mm_s && a.latch_mm_s == b.latch_mm_s &&
         a.position_mm == b.position_mm && a.search_max_mm == b.search_max_mm && a.latch_max_mm == b.latch_max_mm;
}
bool same(const AxisLimits& a, const AxisLimits& b) noexcept {
  return a.position_min_mm == b.position_min_mm && a.position_max_mm == b.position_max_mm &&
         a.speed_max_mm_s == b.speed_max_mm_s && a.following.floor_mm == b.following.floor_mm &&
         a.following.lag_s == b.following.lag_s && a.stall.command_mm_s == b.stall.command_mm_s &&
         a.stall.ticks == b.stall.ticks &&
         a.plausibility.jump_disturbance_scale == b.plausibility.jump_disturbance_scale &&
         a.plausibility.runaway_margin_mm_s == b.plausibility.runaway_margin_mm_s &&
         a.plausibility.runaway_min_command_mm_s == b.plausibility.runaway_min_command_mm_s &&
         a.plausibility.runaway_push_min_command_mm_s == b.plausibility.runaway_push_min_command_mm_s &&
         a.plausibility.runaway_push_fraction == b.plausibility.runaway_push_fraction;
}

// Everything of the force loop but f* (which it takes on line).
bool same_but_force_ref(const arsc::ArscSourceParams& a, const arsc::ArscSourceParams& b) noexcept {
  return a.enabled == b.enabled && a.period_ticks == b.period_ticks && a.pole_re_rad_s == b.pole_re_rad_s &&
         a.pole_im_rad_s == b.pole_im_rad_s && a.force_time_constant_s == b.force_time_constant_s &&
         a.cutting_gain_n_per_mm_s == b.cutting_gain_n_per_mm_s && a.drive_time_constant_s == b.drive_time_constant_s &&
         a.memory_s == b.memory_s && a.gain_min_ratio == b.gain_min_ratio && a.gain_max_ratio == b.gain_max_ratio &&
         a.adapt == b.adapt && a.override_min == b.override_min && a.override_max == b.override_max &&
         a.soft_start_s == b.soft_start_s;
}

}  // namespace

bool TickTask::live_tunable_only(const FirmwareConfig& from, const FirmwareConfig& to) noexcept {
  if (from.supervisor.max_consecutive_missed_ticks != to.supervisor.max_consecutive_missed_ticks) return false;
  if (from.path_tolerance_mm != to.path_tolerance_mm) return false;
  if (from.homing_required != to.homing_required) return false;
  // The force loop: f* and the sensor scale are live, the rest waits for rest (a new loop).
  if (!same_but_force_ref(from.arsc, to.arsc)) return false;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const AxisConfig& a = from.axis[i];
    const AxisConfig& b = to.axis[i];
    if (!same(from.supervisor.axis[i], to.supervisor.axis[i])) return false;
    if (a.count_mm != b.count_mm || a.dac.bits != b.dac.bits || a.dac.full_scale_mm_s != b.dac.full_scale_mm_s ||
        a.controller != b.controller || !same(a.model, b.model) || !same(a.jog, b.jog) ||
        !same(a.friction, b.friction) || !same(a.observer, b.observer) || !same(a.path, b.path) ||
        !same(a.homing, b.homing) || !same(a.screw, b.screw))
      return false;
    // PID: kp, ki, kd and the clamp are live; the filter and the feed-forward switch are not.
    if (a.pid.derivative_filter_tf_s != b.pid.derivative_filter_tf_s || a.pid.feedforward != b.pid.feedforward)
      return false;
    // sliding.*: all live.
  }
  return true;
}

CommandStatus TickTask::apply_config(const FirmwareConfig& config) noexcept {
  // After the first accepted config, only what differs from the running one is checked again.
  if (!(config_validated_ ? validate(config, config_) : validate(config)).ok()) return CommandStatus::invalid;
  if (moving() && !live_tunable_only(config_, config)) return CommandStatus::busy;
  // Everything checked: from here on nothing can refuse, so it applies whole.
  FirmwareConfig next = config;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    AxisConfig& a = next.axis[i];
    const AxisConfig& old = config_.axis[i];
    AxisLoop& loop = axis_[i];
    a.home_position_mm = old.home_position_mm;  // the frame moves with zero() only
    if (!same(a.model, old.model)) {
      loop.pid = PidController(a.model, a.pid);
      loop.dvsc = RdvscController(ControllerKind::dvsc, a.model, a.sliding);
      loop.rdvsc = RdvscController(ControllerKind::rdvsc, a.model, a.sliding);
    } else {
      // Bumpless: each controller keeps its state and re-forms it for the new gains.
      if (!same(a.pid, old.pid)) loop.pid.set_params(a.pid);
      if (!same(a.sliding, old.sliding)) {
        loop.dvsc.set_params(a.sliding);
        loop.rdvsc.set_params(a.sliding);
      }
    }
    if (!same(a.model, old.model) || !same(a.observer, old.observer)) {
      loop.observer.configure(a.model, a.observer);
      loop.observer.reset(record_.axis[i].position_mm, loop.speed_mm_s);
    }
    // The residual's history was formed with the old model and scale.
    if (!same(a.model, old.model) || a.count_mm != old.count_mm || a.dac.full_scale_mm_s != old.dac.full_scale_mm_s)
      plausibility_monitor_[i].reset();
    if (a.count_mm != old.count_mm) {
      // Re-base: the position reading stays where it is, later counts use the new scale.
      const double counts = static_cast<double>(loop.encoder.counts());
      origin_mm_[i] = origin_mm_[i] + counts * old.count_mm - counts * a.count_mm;
    }
    if (a.controller != loop.kind) {
      loop.kind = a.controller;
      if (servo_on()) loop.active().reset();
    }
  }
  // The planner's limits (the soft limits are the supervisor's): at rest only (moving: busy above).
  bool path_changed = next.path_tolerance_mm != config_.path_tolerance_mm;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    path_changed = path_changed || !same(next.axis[i].path, config_.axis[i].path) ||
                   next.supervisor.axis[i].position_min_mm != config_.supervisor.axis[i].position_min_mm ||
                   next.supervisor.axis[i].position_max_mm != config_.supervisor.axis[i].position_max_mm;
  // The force loop: a new loop at rest (validated with the config), f* on line.
  if (!same_but_force_ref(next.arsc, config_.arsc)) (void)arsc_.configure(next.arsc);
  else if (next.arsc.force_ref_n != config_.arsc.force_ref_n) (void)arsc_.set_force_ref_n(next.arsc.force_ref_n);
  config_ = next;
  config_validated_ = true;
  if (path_changed) (void)motion_.configure(path_limits(config_), held_point());  // validated with the config
  return CommandStatus::ok;
}

}  // namespace tnv::fw
