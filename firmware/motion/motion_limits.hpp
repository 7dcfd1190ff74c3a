#pragma once
// Per-axis kinematic limits and path settings of the motion planner,
// validated once before they reach the tick (docs/motion.md).
#include <array>
#include <cstddef>

#include "firmware/control/param_check.hpp"
#include "hal/axis.hpp"

namespace tnv::fw::motion {

struct AxisLimits {
  double speed_mm_s = 100.0;
  double accel_mm_s2 = 500.0;
  double jerk_mm_s3 = 50000.0;
  double position_min_mm = -250.0;  // soft limits: no programmed point beyond them
  double position_max_mm = 250.0;
  bool operator==(const AxisLimits&) const = default;
};

struct MotionLimits {
  std::array<AxisLimits, hal::kAxisCount> axis{};
  double tick_period_s = 1e-3;
  double path_tolerance_mm = 0.005;      // corner blends and arc lag stay within this
  double arc_radius_tolerance_mm = 0.002;
  double min_segment_mm = 0.001;          // shorter lines and arcs are refused as zero length
  double min_arc_radius_mm = 0.01;
  double max_dwell_s = 3600.0;
  bool operator==(const MotionLimits&) const = default;
};

// The jerk filter (a moving average over filter_taps ticks) needs capacity.
inline constexpr std::size_t kMaxFilterTaps = 128;

// The first limit that is wrong: its member in `limits` and why (static
// text); ok when valid.
ParamCheck check(const MotionLimits& limits) noexcept;
// Empty string when valid; otherwise check(limits)'s reason.
const char* validate(const MotionLimits& limits) noexcept;

// Quantities every part of the planner derives from the limits.
struct DerivedLimits {
  double accel_mm_s2 = 0.0;       // smallest axis acceleration: the input path budget
  double path_accel_mm_s2 = 0.0;  // half of it for tangential acceleration
  double dt_s = 1e-3;
  std::size_t filter_taps = 1;    // moving-average length that turns accel into the jerk limit
};

// Requires validate(limits) == "".
DerivedLimits derive(const MotionLimits& limits) noexcept;

}  // namespace tnv::fw::motion
