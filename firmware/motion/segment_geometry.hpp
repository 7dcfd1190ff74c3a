#pragma once
// A segment with its start point and the numbers the planner needs:
// length, tangents at both ends, curvature, and a point at any distance.
#include "firmware/motion/motion_limits.hpp"
#include "firmware/motion/segment.hpp"

namespace tnv::fw::motion {

// Longest profiled element (length / feed + ramp): nothing on the bench
// takes 10^6 s, and its ticks must fit an int64.
inline constexpr double kMaxProfiledDurationS = 1e6;

struct SegmentGeometry {
  SegmentKind kind = SegmentKind::line;
  PlanePoint start_mm{};
  PlanePoint end_mm{};
  PlanePoint centre_mm{};
  ArcPlane plane = ArcPlane::xy;  // arcs: start_angle_rad and sweep_rad are measured in it
  double length_mm = 0.0;       // 0 for a dwell
  double start_radius_mm = 0.0; // arcs: radius at the start; it moves linearly to the end radius
  double end_radius_mm = 0.0;
  double start_angle_rad = 0.0;
  double sweep_rad = 0.0;       // signed: counter-clockwise positive
  PlanePoint unit_start{};      // tangent at the start (unit)
  PlanePoint unit_end{};        // tangent at the end (unit)

  PlanePoint point_at(double distance_mm) const noexcept;
  // An arc's point at `fraction` (0 ... 1) of its sweep: angle and radius
  // in its plane, every other axis (a helix' third) linearly with the angle.
  PlanePoint arc_point(double fraction) const noexcept;
  // Largest path speed the axis speed limits allow anywhere on the element.
  double axis_speed_cap_mm_s(const MotionLimits& limits) const noexcept;
  double min_radius_mm() const noexcept { return start_radius_mm < end_radius_mm ? start_radius_mm : end_radius_mm; }
};

// Checks a segment that starts at start_mm; on success fills out and
// returns none, on refusal returns the reason and leaves out untouched.
SegmentRefusal prepare(const Segment& segment, const PlanePoint& start_mm, const MotionLimits& limits,
                       SegmentGeometry& out) noexcept;

}  // namespace tnv::fw::motion
