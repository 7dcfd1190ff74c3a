#include "firmware/trajectory/circle_trajectory.hpp"

namespace tnv::fw {

const char* validate(const CircleSpec& spec) noexcept {
  if (!std::isfinite(spec.radius_mm) || spec.radius_mm <= 0.0) return "radius_mm must be > 0 and finite";
  if (!std::isfinite(spec.feed_mm_s) || spec.feed_mm_s <= 0.0) return "feed_mm_s must be > 0 and finite";
  if (!std::isfinite(spec.ramp_s) || spec.ramp_s < 0.0) return "ramp_s must be >= 0 and finite";
  if (!std::isfinite(spec.dwell_s) || spec.dwell_s < 0.0) return "dwell_s must be >= 0 and finite";
  if (spec.feed_mm_s * spec.ramp_s > 2.0 * std::numbers::pi * spec.radius_mm)
    return "ramp_s too long: the two feed ramps do not fit in the circle";
  // The tick task counts a motion's ticks in an int64 (found by fuzzing: a
  // feed of 1e-40 mm/s overflowed it); nothing on the bench takes 10^6 s.
  if (spec.dwell_s > 1e6) return "dwell_s must be <= 1e6 s";
  if (2.0 * std::numbers::pi * spec.radius_mm / spec.feed_mm_s + spec.ramp_s > 1e6)
    return "feed_mm_s too low for radius_mm: the circle would take more than 1e6 s";
  return "";
}

}  // namespace tnv::fw
