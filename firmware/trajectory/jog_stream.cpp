#include "firmware/trajectory/jog_stream.hpp"

#include <cmath>

namespace tnv::fw {

ParamCheck validate(const JogLimits& limits) noexcept {
  if (!std::isfinite(limits.speed_max_mm_s) || limits.speed_max_mm_s <= 0.0)
    return param_error("speed_max_mm_s", "must be > 0 and finite");
  if (!std::isfinite(limits.accel_mm_s2) || limits.accel_mm_s2 <= 0.0)
    return param_error("accel_mm_s2", "must be > 0 and finite");
  if (!std::isfinite(limits.deadman_s) || limits.deadman_s <= 0.0)
    return param_error("deadman_s", "must be > 0 and finite");
  return param_ok();
}

void JogStream::start(double position_mm) noexcept {
  now_ = {position_mm, 0.0};
  target_mm_s_ = 0.0;
  silence_s_ = 0.0;
}

bool JogStream::command(double speed_mm_s) noexcept {
  if (!std::isfinite(speed_mm_s) || std::fabs(speed_mm_s) > limits_.speed_max_mm_s) return false;
  target_mm_s_ = speed_mm_s;
  silence_s_ = 0.0;
  return true;
}

AxisSample JogStream::advance(double period_s) noexcept {
  silence_s_ += period_s;
  if (silence_s_ > limits_.deadman_s && target_mm_s_ != 0.0) {
    target_mm_s_ = 0.0;  // the operator went quiet: stop
    ++deadman_stops_;
  }
  const double step_mm_s = limits_.accel_mm_s2 * period_s;
  const double v0 = now_.speed_mm_s;
  const double gap = target_mm_s_ - v0;
  // Reach the target exactly (v == 0.0 at rest), never overshoot it.
  const double v1 = std::fabs(gap) <= step_mm_s ? target_mm_s_ : v0 + (gap > 0.0 ? step_mm_s : -step_mm_s);
  now_.position_mm += 0.5 * (v0 + v1) * period_s;  // exact for a linear speed
  now_.speed_mm_s = v1;
  return now_;
}

}  // namespace tnv::fw
