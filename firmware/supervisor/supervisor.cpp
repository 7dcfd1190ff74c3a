#include "firmware/supervisor/supervisor.hpp"

namespace tnv::fw {

namespace {

bool finite_positive(double v) noexcept { return std::isfinite(v) && v > 0.0; }

constexpr std::uint32_t kMaxStallTicks = 1000;

FaultRecord fault(FaultReason reason, const SupervisorInput& in, int axis = -1, double value = 0.0,
                  double limit = 0.0) noexcept {
  return {reason, static_cast<std::int8_t>(axis), in.tick, value, limit};
}

}  // namespace

ParamCheck check(const SupervisorConfig& config) noexcept {
  for (const AxisLimits& a : config.axis) {
    if (!std::isfinite(a.position_min_mm) || !std::isfinite(a.position_max_mm) ||
        a.position_min_mm >= a.position_max_mm)
      return param_error(&a.position_min_mm, "position_min_mm", "position limits must be finite with min < max");
    if (!finite_positive(a.speed_max_mm_s))
      return param_error(&a.speed_max_mm_s, "speed_max_mm_s", "speed_max_mm_s must be > 0 and finite");
    if (!finite_positive(a.following.floor_mm))
      return param_error(&a.following.floor_mm, "following.floor_mm",
                         "following-error floor_mm must be > 0 and finite");
    if (!std::isfinite(a.following.lag_s) || a.following.lag_s < 0.0)
      return param_error(&a.following.lag_s, "following.lag_s", "following-error lag_s must be >= 0 and finite");
    if (!finite_positive(a.stall.command_mm_s))
      return param_error(&a.stall.command_mm_s, "stall.command_mm_s", "stall command_mm_s must be > 0 and finite");
    if (a.stall.ticks < 1 || a.stall.ticks > kMaxStallTicks)
      return param_error(&a.stall.ticks, "stall.ticks", "stall ticks must be 1..1000");
    const PlausibilityLimit& p = a.plausibility;
    if (!(p.jump_disturbance_scale >= 0.5 && p.jump_disturbance_scale <= 4.0))
      return param_error(&p.jump_disturbance_scale, "plausibility.jump_disturbance_scale",
                         "plausibility jump_disturbance_scale must be 0.5..4");
    if (!(p.runaway_margin_mm_s >= 0.0 && p.runaway_margin_mm_s <= 100.0))
      return param_error(&p.runaway_margin_mm_s, "plausibility.runaway_margin_mm_s",
                         "plausibility runaway_margin_mm_s must be 0..100");
    if (!(p.runaway_min_command_mm_s > 0.0 && p.runaway_min_command_mm_s <= 100.0))
      return param_error(&p.runaway_min_command_mm_s, "plausibility.runaway_min_command_mm_s",
                         "plausibility runaway_min_command_mm_s must be > 0 and <= 100");
    if (!(p.runaway_push_min_command_mm_s >= 1.0 && p.runaway_push_min_command_mm_s <= 100.0))
      return param_error(&p.runaway_push_min_command_mm_s, "plausibility.runaway_push_min_command_mm_s",
                         "plausibility runaway_push_min_command_mm_s must be 1..100");
    if (!(p.runaway_push_fraction >= 0.1 && p.runaway_push_fraction <= 1.0))
      return param_error(&p.runaway_push_fraction, "plausibility.runaway_push_fraction",
                         "plausibility runaway_push_fraction must be 0.1..1");
  }
  if (config.tick_period_clocks == 0)
    return param_error(&config.tick_period_clocks, "tick_period_clocks", "tick_period_clocks must be > 0");
  if (config.period_tolerance_clocks == 0 || config.period_tolerance_clocks >= config.tick_period_clocks)
    return param_error(&config.period_tolerance_clocks, "period_tolerance_clocks",
                       "period_tolerance_clocks must be > 0 and below tick_period_clocks");
  return param_ok();
}

const char* validate(const SupervisorConfig& config) noexcept { return check(config).reason; }

FaultRecord check(const SupervisorConfig& config, const SupervisorInput& in) noexcept {
  if (!in.bus_ok) return fault(FaultReason::bus_error, in);
  if (!in.snapshot_advanced) return fault(FaultReason::stale_snapshot, in);
  if (in.ticks_missed > config.max_consecutive_missed_ticks)
    return fault(FaultReason::missed_ticks, in, -1, in.ticks_missed, config.max_consecutive_missed_ticks);
  if (in.period_clocks != 0) {
    // The period spans ticks_missed + 1 nominal periods (in 64 bits: no overflow).
    const std::uint64_t expected = std::uint64_t{config.tick_period_clocks} * (std::uint64_t{in.ticks_missed} + 1);
    const std::uint64_t period = in.period_clocks;
    const std::uint64_t off = period > expected ? period - expected : expected - period;
    if (off > config.period_tolerance_clocks)
      return fault(FaultReason::late_tick, in, -1, static_cast<double>(period), static_cast<double>(expected));
  }
  if (in.inputs.estop) return fault(FaultReason::estop, in);
  if (in.inputs.watchdog_tripped) return fault(FaultReason::watchdog_tripped, in);
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const int axis = static_cast<int>(i);
    if (in.inputs.servo_alarm[i]) return fault(FaultReason::servo_alarm, in, axis);
    if (in.inputs.limit_positive[i] || in.inputs.limit_negative[i]) return fault(FaultReason::limit_switch, in, axis);
    if (in.inputs.encoder_error[i]) return fault(FaultReason::encoder_error, in, axis);
    if (in.inputs.dac_error[i]) return fault(FaultReason::dac_error, in, axis);
    // A count the table cannot have made: before anything computed from it.
    if (const PlausibilityVerdict& p = in.axis[i].plausibility; p.jump)
      return fault(FaultReason::encoder_implausible, in, axis, p.step_mm - p.predicted_mm, p.spread_mm);
  }
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const int axis = static_cast<int>(i);
    const AxisLimits& lim = config.axis[i];
    const AxisCheckInput& a = in.axis[i];
    if (a.soft_limits && a.position_mm < lim.position_min_mm) return fault(FaultReason::position_limit, in, axis, a.position_mm, lim.position_min_mm);
    if (a.soft_limits && a.position_mm > lim.position_max_mm) return fault(FaultReason::position_limit, in, axis, a.position_mm, lim.position_max_mm);
    if (std::fabs(a.speed_mm_s) > lim.speed_max_mm_s)
      return fault(FaultReason::speed_limit, in, axis, a.speed_mm_s, lim.speed_max_mm_s);
    if (!in.servo_on) continue;
    if (!std::isfinite(a.command_mm_s)) return fault(FaultReason::non_finite_command, in, axis);
    if (a.plausibility.runaway)
      return fault(FaultReason::runaway, in, axis, a.plausibility.against_mm, a.plausibility.against_limit_mm);
    if (a.plausibility.runaway_push)  // value in mm/s (the input against the command), not mm
      return fault(FaultReason::runaway, in, axis, a.plausibility.push_against_mm_s, a.plausibility.push_limit_mm_s);
    // Before the following error: a frozen count is the root cause it would only see later.
    if (a.stalled_ticks >= lim.stall.ticks)
      return fault(FaultReason::encoder_stall, in, axis, a.stall_command_mm_s, lim.stall.command_mm_s);
    const double error_mm = a.reference_mm - a.position_mm;
    const double limit_mm = lim.following.at(a.reference_speed_mm_s);
    if (!(std::fabs(error_mm) <= limit_mm)) return fault(FaultReason::following_error, in, axis, error_mm, limit_mm);
  }
  return {};
}

bool fault_cause_present(const hal::DiscreteInputs& in) noexcept {
  bool cause = in.estop || in.watchdog_tripped;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    cause = cause || in.servo_alarm[i] || in.limit_positive[i] || in.limit_negative[i] || in.encoder_error[i] ||
            in.dac_error[i];
  }
  return cause;
}

}  // namespace tnv::fw
