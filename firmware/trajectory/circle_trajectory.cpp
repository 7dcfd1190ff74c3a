#include "firmware/trajectory/circle_trajectory.hpp"

namespace tnv::fw {

const char* validate(const CircleSpec& spec) noexcept {
  if (!std::isfinite(spec.radius_mm) || spec.radius_mm <= 0.0) return "radius_mm must be > 0 and finite";
  if (!std::isfinite(spec.feed_mm_s) || spec.feed_mm_s <= 0.0) return "feed_mm_s must be > 0 and finite";
  if (!std::isfinite(spec.ramp_s) || spec.ramp_s < 0.0) return "ramp_s must be >= 0 and finite";
  if (!std::isfinite(spec.dwell_s) || spec.dwell_s < 0.0) return "dwell_s must be >= 0 and finite";
  if (spec.feed_mm_s * spec.ramp_s > 2.0 * std::numbers::pi * spec.radius_mm)
    return "ramp_s too long: the two feed ramps do not fit in the circle";
  return "";
}

}  // namespace tnv::fw
