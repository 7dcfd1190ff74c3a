#pragma once
// The S1 circle and the point-to-point move as producers of segments: each
// is one profiled element (Segment::ramp_s, profiled_run.hpp) with the
// raised-cosine feed ramps of the reference plant's circle experiment.
#include "firmware/motion/segment.hpp"
#include "firmware/trajectory/circle_trajectory.hpp"
#include "firmware/trajectory/point_to_point_move.hpp"

namespace tnv::fw::motion {

// Where the circle starts and ends: its centre + (radius, 0).
constexpr PlanePoint circle_start_mm(const CircleSpec& spec, const PlanePoint& centre_mm) noexcept {
  PlanePoint start = centre_mm;  // the other axes where the centre is
  start[hal::index(hal::kPlaneFirst)] += spec.radius_mm;
  return start;
}

// A full counter-clockwise circle from circle_start_mm() back to it.
constexpr Segment circle_segment(const CircleSpec& spec, const PlanePoint& centre_mm) noexcept {
  Segment s = arc_to(false, circle_start_mm(spec, centre_mm), centre_mm, spec.feed_mm_s);
  s.ramp_s = spec.ramp_s;
  return s;
}

// spec.distance_mm along spec.axis from start_mm; the other axis stays.
constexpr Segment move_segment(const MoveSpec& spec, const PlanePoint& start_mm) noexcept {
  PlanePoint end = start_mm;
  end[hal::index(spec.axis)] += spec.distance_mm;
  Segment s = line_to(end, spec.speed_mm_s);
  s.ramp_s = spec.ramp_s;
  return s;
}

}  // namespace tnv::fw::motion
