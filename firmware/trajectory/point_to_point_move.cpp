#include "firmware/trajectory/point_to_point_move.hpp"

namespace tnv::fw {

const char* validate(const MoveSpec& spec) noexcept {
  if (hal::index(spec.axis) >= hal::kAxisCount) return "axis must be one of the machine's axes";
  if (!std::isfinite(spec.distance_mm) || spec.distance_mm == 0.0) return "distance_mm must be finite and non-zero";
  if (!std::isfinite(spec.speed_mm_s) || spec.speed_mm_s <= 0.0) return "speed_mm_s must be > 0 and finite";
  if (!std::isfinite(spec.ramp_s) || spec.ramp_s < 0.0) return "ramp_s must be >= 0 and finite";
  if (!std::isfinite(spec.dwell_s) || spec.dwell_s < 0.0) return "dwell_s must be >= 0 and finite";
  if (spec.speed_mm_s * spec.ramp_s > std::fabs(spec.distance_mm))
    return "ramp_s too long for distance_mm at speed_mm_s: the two ramps do not fit (speed * ramp <= |distance|)";
  // The tick task counts a motion's ticks in an int64; nothing on the bench takes 10^6 s.
  if (spec.dwell_s > 1e6) return "dwell_s must be <= 1e6 s";
  if (std::fabs(spec.distance_mm) / spec.speed_mm_s + spec.ramp_s > 1e6)
    return "speed_mm_s too low for distance_mm: the move would take more than 1e6 s";
  return "";
}

}  // namespace tnv::fw
