#include "firmware/trajectory/jog_limits.hpp"

#include <cmath>

namespace tnv::fw {

ParamCheck validate(const JogLimits& limits) noexcept {
  if (!std::isfinite(limits.speed_max_mm_s) || limits.speed_max_mm_s <= 0.0)
    return param_error(&limits.speed_max_mm_s, "speed_max_mm_s", "must be > 0 and finite");
  if (!std::isfinite(limits.accel_mm_s2) || limits.accel_mm_s2 <= 0.0)
    return param_error(&limits.accel_mm_s2, "accel_mm_s2", "must be > 0 and finite");
  if (!std::isfinite(limits.deadman_s) || limits.deadman_s <= 0.0)
    return param_error(&limits.deadman_s, "deadman_s", "must be > 0 and finite");
  return param_ok();
}

}  // namespace tnv::fw
