#include "firmware/motion/motion_limits.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::fw::motion {

namespace {

bool positive_finite(double v) noexcept { return std::isfinite(v) && v > 0.0; }

double filter_taps_exact(const MotionLimits& limits) noexcept {
  // Output jerk of the moving average is at most 2 * a_in / (taps * dt)
  // (the input acceleration can swing from +a to -a), so taps >= 2 a_i / (j_i dt)
  // on every axis: each axis' point acceleration is within its own a_i.
  double taps = 1.0;
  for (const AxisLimits& a : limits.axis)
    taps = std::max(taps, 2.0 * a.accel_mm_s2 / (a.jerk_mm_s3 * limits.tick_period_s));
  return taps;
}

}  // namespace

ParamCheck check(const MotionLimits& limits) noexcept {
  for (const AxisLimits& a : limits.axis) {
    if (!positive_finite(a.speed_mm_s))
      return param_error(&a.speed_mm_s, "speed_mm_s", "axis speed_mm_s must be > 0 and finite");
    if (!positive_finite(a.accel_mm_s2))
      return param_error(&a.accel_mm_s2, "accel_mm_s2", "axis accel_mm_s2 must be > 0 and finite");
    if (!positive_finite(a.jerk_mm_s3))
      return param_error(&a.jerk_mm_s3, "jerk_mm_s3", "axis jerk_mm_s3 must be > 0 and finite");
    if (!std::isfinite(a.position_min_mm) || !std::isfinite(a.position_max_mm) || a.position_min_mm >= a.position_max_mm)
      return param_error(&a.position_min_mm, "position_min_mm",
                         "axis position_min_mm must be below position_max_mm, both finite");
  }
  if (!positive_finite(limits.tick_period_s) || limits.tick_period_s > 0.1)
    return param_error(&limits.tick_period_s, "tick_period_s", "tick_period_s must be in (0, 0.1]");
  if (!positive_finite(limits.path_tolerance_mm))
    return param_error(&limits.path_tolerance_mm, "path_tolerance_mm", "path_tolerance_mm must be > 0 and finite");
  if (!positive_finite(limits.arc_radius_tolerance_mm))
    return param_error(&limits.arc_radius_tolerance_mm, "arc_radius_tolerance_mm",
                       "arc_radius_tolerance_mm must be > 0 and finite");
  if (!positive_finite(limits.min_segment_mm))
    return param_error(&limits.min_segment_mm, "min_segment_mm", "min_segment_mm must be > 0 and finite");
  if (!positive_finite(limits.min_arc_radius_mm))
    return param_error(&limits.min_arc_radius_mm, "min_arc_radius_mm", "min_arc_radius_mm must be > 0 and finite");
  if (!positive_finite(limits.max_dwell_s))
    return param_error(&limits.max_dwell_s, "max_dwell_s", "max_dwell_s must be > 0 and finite");
  // The filter's length comes from the axis with the largest acceleration over jerk: name its jerk.
  if (std::ceil(filter_taps_exact(limits)) > static_cast<double>(kMaxFilterTaps)) {
    const AxisLimits* worst = &limits.axis[0];
    for (const AxisLimits& a : limits.axis)
      if (a.accel_mm_s2 / a.jerk_mm_s3 > worst->accel_mm_s2 / worst->jerk_mm_s3) worst = &a;
    return param_error(&worst->jerk_mm_s3, "jerk_mm_s3",
                       "jerk limits too low for the acceleration limits: the jerk filter would need more than 128 taps");
  }
  return param_ok();
}

const char* validate(const MotionLimits& limits) noexcept { return check(limits).reason; }

DerivedLimits derive(const MotionLimits& limits, double path_accel_cap_mm_s2) noexcept {
  DerivedLimits d;
  double smallest = limits.axis[0].accel_mm_s2;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    d.axis_accel_mm_s2[i] = limits.axis[i].accel_mm_s2;
    smallest = std::min(smallest, limits.axis[i].accel_mm_s2);
  }
  d.dt_s = limits.tick_period_s;
  d.filter_taps = static_cast<std::size_t>(std::ceil(filter_taps_exact(limits) - 1e-9));
  if (d.filter_taps < 1) d.filter_taps = 1;
  const double window_s = static_cast<double>(d.filter_taps) * d.dt_s;
  d.path_accel_cap_mm_s2 = kCornerRoundingShare * 48.0 * limits.path_tolerance_mm / (window_s * window_s);
  if (path_accel_cap_mm_s2 > 0.0) d.path_accel_cap_mm_s2 = std::min(d.path_accel_cap_mm_s2, path_accel_cap_mm_s2);
  // Along any direction the envelope is at least the smallest axis limit.
  d.path_accel_mm_s2 = std::min(kTangentShare * smallest, d.path_accel_cap_mm_s2);
  return d;
}

double line_accel_mm_s2(const DerivedLimits& d, const PlanePoint& unit) noexcept {
  double envelope = 1e300;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    if (const double u = std::fabs(unit[i]); u > 1e-12) envelope = std::min(envelope, d.axis_accel_mm_s2[i] / u);
  return std::min(kTangentShare * envelope, d.path_accel_cap_mm_s2);
}

}  // namespace tnv::fw::motion
