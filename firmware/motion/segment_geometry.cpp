#include "firmware/motion/segment_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tnv::fw::motion {

namespace {

bool finite(const PlanePoint& p) noexcept {
  for (const double v : p)
    if (!std::isfinite(v)) return false;
  return true;
}

// A path of plane_mm in the plane that also moves each further axis from a
// to b (a line's, a helix's): hypot with each further axis' travel in turn
// (hypot(h, 0) is h exactly, so a path in the plane keeps its length bit for bit).
double with_axes_beyond_plane(double plane_mm, const PlanePoint& a, const PlanePoint& b) noexcept {
  for (std::size_t i = 2; i < hal::kAxisCount; ++i) plane_mm = std::hypot(plane_mm, b[i] - a[i]);
  return plane_mm;
}

// |b - a| over every axis.
double distance_mm(const PlanePoint& a, const PlanePoint& b) noexcept {
  return with_axes_beyond_plane(std::hypot(b[0] - a[0], b[1] - a[1]), a, b);
}

bool inside(const PlanePoint& p, const MotionLimits& limits) noexcept {
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    if (!(p[i] >= limits.axis[i].position_min_mm && p[i] <= limits.axis[i].position_max_mm)) return false;
  return true;
}

// Tangent of an arc at angle theta; ccw: +90 degrees from the radius vector.
PlanePoint arc_tangent(double theta, bool ccw) noexcept {
  const double sign = ccw ? 1.0 : -1.0;
  PlanePoint t{};
  t[0] = -sign * std::sin(theta);
  t[1] = sign * std::cos(theta);
  return t;
}

// A profiled element's two raised-cosine ramps must fit its length, and its
// time law must stay countable in ticks (the tick task counts in int64).
SegmentRefusal check_ramp(const Segment& segment, double length_mm) noexcept {
  if (!std::isfinite(segment.ramp_s)) return SegmentRefusal::not_finite;
  if (segment.ramp_s < 0.0) return SegmentRefusal::bad_ramp;
  if (segment.ramp_s == 0.0) return SegmentRefusal::none;
  if (segment.feed_mm_s * segment.ramp_s > length_mm) return SegmentRefusal::bad_ramp;
  if (length_mm / segment.feed_mm_s + segment.ramp_s > kMaxProfiledDurationS) return SegmentRefusal::bad_ramp;
  return SegmentRefusal::none;
}

}  // namespace

PlanePoint SegmentGeometry::point_at(double distance_mm) const noexcept {
  if (kind == SegmentKind::dwell || length_mm <= 0.0) return start_mm;
  const double f = std::clamp(distance_mm / length_mm, 0.0, 1.0);
  if (kind == SegmentKind::line) {
    PlanePoint p{};
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) p[i] = start_mm[i] + f * (end_mm[i] - start_mm[i]);
    return p;
  }
  if (f >= 1.0) return end_mm;
  const double theta = start_angle_rad + f * sweep_rad;
  const double r = start_radius_mm + f * (end_radius_mm - start_radius_mm);
  // An arc is in the XY plane; the other axes (Z: a helix) move in step with its angle.
  PlanePoint p = start_mm;
  p[0] = centre_mm[0] + r * std::cos(theta);
  p[1] = centre_mm[1] + r * std::sin(theta);
  for (std::size_t i = 2; i < hal::kAxisCount; ++i) p[i] = start_mm[i] + f * (end_mm[i] - start_mm[i]);
  return p;
}

double SegmentGeometry::axis_speed_cap_mm_s(const MotionLimits& limits) const noexcept {
  double cap = 1e300;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const double v = limits.axis[i].speed_mm_s;
    if (kind != SegmentKind::line) {
      cap = std::min(cap, v);  // an arc may sweep along any axis
    } else if (const double u = std::fabs(unit_start[i]); u > 1e-12) {
      cap = std::min(cap, v / u);
    }
  }
  return cap;
}

SegmentRefusal prepare(const Segment& segment, const PlanePoint& start_mm, const MotionLimits& limits,
                       SegmentGeometry& out) noexcept {
  SegmentGeometry g;
  g.kind = segment.kind;
  g.start_mm = start_mm;
  // A pause or a spindle command is a dwell, and one element is not both.
  if (is_program_action(segment) && (segment.kind != SegmentKind::dwell || (segment.pause && segment.spindle != SpindleChange::none)))
    return SegmentRefusal::bad_kind;
  // A probe is a feed line (not a rapid, not a profiled element) and ends at rest.
  if (segment.probe != ProbeKind::none &&
      (static_cast<std::uint8_t>(segment.probe) > static_cast<std::uint8_t>(ProbeKind::away) ||
       segment.kind != SegmentKind::line || segment.rapid || segment.profiled() || !segment.exact_stop ||
       is_program_action(segment)))
    return SegmentRefusal::bad_kind;
  if (segment.spindle == SpindleChange::forward || segment.spindle == SpindleChange::reverse) {
    if (!std::isfinite(segment.spindle_rpm)) return SegmentRefusal::not_finite;
    if (segment.spindle_rpm <= 0.0) return SegmentRefusal::bad_spindle;
  }
  switch (segment.kind) {
    case SegmentKind::dwell: {
      if (!std::isfinite(segment.dwell_s) || !std::isfinite(segment.ramp_s)) return SegmentRefusal::not_finite;
      if (segment.ramp_s != 0.0) return SegmentRefusal::bad_ramp;
      if (is_program_action(segment) ? segment.dwell_s != 0.0
                                     : segment.dwell_s <= 0.0 || segment.dwell_s > limits.max_dwell_s)
        return SegmentRefusal::bad_dwell;
      g.end_mm = start_mm;
      out = g;
      return SegmentRefusal::none;
    }
    case SegmentKind::line: {
      if (!finite(segment.end_mm) || !std::isfinite(segment.feed_mm_s)) return SegmentRefusal::not_finite;
      g.length_mm = distance_mm(start_mm, segment.end_mm);
      if (!(g.length_mm >= limits.min_segment_mm)) return SegmentRefusal::zero_length;
      g.end_mm = segment.end_mm;
      for (std::size_t i = 0; i < hal::kAxisCount; ++i)
        g.unit_start[i] = (segment.end_mm[i] - start_mm[i]) / g.length_mm;
      g.unit_end = g.unit_start;
      break;
    }
    case SegmentKind::arc_cw:
    case SegmentKind::arc_ccw: {
      if (!finite(segment.end_mm) || !finite(segment.centre_mm) || !std::isfinite(segment.feed_mm_s))
        return SegmentRefusal::not_finite;
      const bool ccw = segment.kind == SegmentKind::arc_ccw;
      const PlanePoint& c = segment.centre_mm;
      g.centre_mm = c;
      g.end_mm = segment.end_mm;
      g.start_radius_mm = std::hypot(start_mm[0] - c[0], start_mm[1] - c[1]);
      g.end_radius_mm = std::hypot(segment.end_mm[0] - c[0], segment.end_mm[1] - c[1]);
      if (std::fabs(g.start_radius_mm - g.end_radius_mm) > limits.arc_radius_tolerance_mm)
        return SegmentRefusal::arc_radius_mismatch;
      if (g.min_radius_mm() < limits.min_arc_radius_mm) return SegmentRefusal::arc_radius_too_small;
      g.start_angle_rad = std::atan2(start_mm[1] - c[1], start_mm[0] - c[0]);
      const double end_angle = std::atan2(segment.end_mm[1] - c[1], segment.end_mm[0] - c[0]);
      constexpr double two_pi = 2.0 * std::numbers::pi;
      double sweep = end_angle - g.start_angle_rad;
      if (ccw) {
        while (sweep <= 0.0) sweep += two_pi;
      } else {
        while (sweep >= 0.0) sweep -= two_pi;
      }
      // End on the start point (within the minimum length): a full circle.
      const bool closed = std::hypot(segment.end_mm[0] - start_mm[0], segment.end_mm[1] - start_mm[1]) <
                          limits.min_segment_mm;
      if (closed) sweep = ccw ? two_pi : -two_pi;
      g.sweep_rad = sweep;
      // A helix: the plane's arc length and each further axis' travel, as a line's.
      const double plane_mm = 0.5 * (g.start_radius_mm + g.end_radius_mm) * std::fabs(sweep);
      g.length_mm = with_axes_beyond_plane(plane_mm, start_mm, segment.end_mm);
      if (!(g.length_mm >= limits.min_segment_mm)) return SegmentRefusal::zero_length;
      const double in_plane = plane_mm / g.length_mm;
      g.unit_start = arc_tangent(g.start_angle_rad, ccw);
      g.unit_end = arc_tangent(g.start_angle_rad + sweep, ccw);
      for (std::size_t i = 0; i < 2; ++i) {
        g.unit_start[i] *= in_plane;
        g.unit_end[i] *= in_plane;
      }
      for (std::size_t i = 2; i < hal::kAxisCount; ++i)
        g.unit_start[i] = g.unit_end[i] = (segment.end_mm[i] - start_mm[i]) / g.length_mm;
      break;
    }
    default: return SegmentRefusal::bad_kind;
  }
  if (!inside(g.end_mm, limits)) return SegmentRefusal::outside_workspace;
  if (!(segment.feed_mm_s > 0.0)) return SegmentRefusal::feed_not_positive;
  if (segment.feed_mm_s > g.axis_speed_cap_mm_s(limits) * (1.0 + 1e-12)) return SegmentRefusal::feed_above_limit;
  if (const SegmentRefusal r = check_ramp(segment, g.length_mm); r != SegmentRefusal::none) return r;
  out = g;
  return SegmentRefusal::none;
}

}  // namespace tnv::fw::motion
