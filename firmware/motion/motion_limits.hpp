#pragma once
// Per-axis kinematic limits and path settings of the motion planner,
// validated once before they reach the tick (docs/motion.md).
#include <array>
#include <cstddef>

#include "firmware/control/param_check.hpp"
#include "firmware/motion/segment.hpp"
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

// Highest feed override (the planner sizes an arc's tangential acceleration for it).
inline constexpr double kMaxFeedOverride = 1.5;

// The per-axis envelope (docs/motion.md "Per-axis envelope"). Along a line
// the path accelerates at this share of the largest rate every axis allows
// in its direction; the rest of each axis' limit is what a sharp corner's
// turn may take in the tick that crosses it.
inline constexpr double kTangentShare = 0.95;
// An arc's centripetal acceleration stays within this share of its axes'
// smallest limit, so that sqrt(tangential^2 + centripetal^2) <= kTangentShare
// leaves its tangential acceleration at least 0.3 of it.
inline constexpr double kCentripetalShare = 0.9;
// A line gives up tangential acceleration so that the corner at its start
// can be crossed at the programmed feed, but keeps at least this share of
// its own rate; a corner that needs more is a near-stop instead.
inline constexpr double kTangentFloorShare = 0.3;
// A corner the path nearly stops at, braked into and left at A: the jerk
// filter's mean of the two sides stays within A T^2 / 48 of them (T the
// filter's window). Every path acceleration is capped at this share of
// 48 eps / T^2, so that rounding stays within the path tolerance eps.
inline constexpr double kCornerRoundingShare = 0.9;

// The first limit that is wrong: its member in `limits` and why (static
// text); ok when valid.
ParamCheck check(const MotionLimits& limits) noexcept;
// Empty string when valid; otherwise check(limits)'s reason.
const char* validate(const MotionLimits& limits) noexcept;

// Quantities every part of the planner derives from the limits.
struct DerivedLimits {
  // Each axis' own acceleration limit: the budget of the path point's
  // per-axis second difference (a_i dt^2), so of the reference's too.
  std::array<double, hal::kAxisCount> axis_accel_mm_s2{};
  // Smallest tangential acceleration of any line (the jog's lead distance).
  double path_accel_mm_s2 = 0.0;
  // Cap of every path acceleration: the corner rounding's (above) and the
  // jog's own limit.
  double path_accel_cap_mm_s2 = 1e300;
  double dt_s = 1e-3;
  std::size_t filter_taps = 1;    // moving-average length that turns accel into the jerk limit
};

// Requires validate(limits) == "". With path_accel_cap_mm_s2 > 0 no path
// acceleration exceeds it (the jog's limit).
DerivedLimits derive(const MotionLimits& limits, double path_accel_cap_mm_s2 = 0.0) noexcept;

// Tangential acceleration of a line along `unit`: kTangentShare of the
// largest value with |unit_i| * value <= a_i on every axis, within the cap.
double line_accel_mm_s2(const DerivedLimits& d, const PlanePoint& unit) noexcept;

}  // namespace tnv::fw::motion
