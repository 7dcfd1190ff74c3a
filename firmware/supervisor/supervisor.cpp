#include "firmware/supervisor/supervisor.hpp"

namespace tnv::fw {

namespace {

bool finite_positive(double v) noexcept { return std::isfinite(v) && v > 0.0; }

FaultRecord fault(FaultReason reason, const SupervisorInput& in, int axis = -1, double value = 0.0,
                  double limit = 0.0) noexcept {
  return {reason, static_cast<std::int8_t>(axis), in.tick, value, limit};
}

}  // namespace

const char* validate(const SupervisorConfig& config) noexcept {
  for (const AxisLimits& a : config.axis) {
    if (!std::isfinite(a.position_min_mm) || !std::isfinite(a.position_max_mm) ||
        a.position_min_mm >= a.position_max_mm)
      return "position limits must be finite with min < max";
    if (!finite_positive(a.speed_max_mm_s)) return "speed_max_mm_s must be > 0 and finite";
    if (!finite_positive(a.following.floor_mm)) return "following-error floor_mm must be > 0 and finite";
    if (!std::isfinite(a.following.lag_s) || a.following.lag_s < 0.0)
      return "following-error lag_s must be >= 0 and finite";
  }
  return "";
}

FaultRecord check(const SupervisorConfig& config, const SupervisorInput& in) noexcept {
  if (!in.bus_ok) return fault(FaultReason::bus_error, in);
  if (!in.snapshot_advanced) return fault(FaultReason::stale_snapshot, in);
  if (in.ticks_missed > config.max_consecutive_missed_ticks)
    return fault(FaultReason::missed_ticks, in, -1, in.ticks_missed, config.max_consecutive_missed_ticks);
  if (in.inputs.estop) return fault(FaultReason::estop, in);
  if (in.inputs.watchdog_tripped) return fault(FaultReason::watchdog_tripped, in);
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const int axis = static_cast<int>(i);
    if (in.inputs.servo_alarm[i]) return fault(FaultReason::servo_alarm, in, axis);
    if (in.inputs.limit_positive[i] || in.inputs.limit_negative[i]) return fault(FaultReason::limit_switch, in, axis);
  }
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const int axis = static_cast<int>(i);
    const AxisLimits& lim = config.axis[i];
    const AxisCheckInput& a = in.axis[i];
    if (a.position_mm < lim.position_min_mm) return fault(FaultReason::position_limit, in, axis, a.position_mm, lim.position_min_mm);
    if (a.position_mm > lim.position_max_mm) return fault(FaultReason::position_limit, in, axis, a.position_mm, lim.position_max_mm);
    if (std::fabs(a.speed_mm_s) > lim.speed_max_mm_s)
      return fault(FaultReason::speed_limit, in, axis, a.speed_mm_s, lim.speed_max_mm_s);
    if (!in.servo_on) continue;
    if (!std::isfinite(a.command_mm_s)) return fault(FaultReason::non_finite_command, in, axis);
    const double error_mm = a.reference_mm - a.position_mm;
    const double limit_mm = lim.following.at(a.reference_speed_mm_s);
    if (!(std::fabs(error_mm) <= limit_mm)) return fault(FaultReason::following_error, in, axis, error_mm, limit_mm);
  }
  return {};
}

}  // namespace tnv::fw
