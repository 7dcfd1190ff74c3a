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
// to b (a line's, a helix's): hypot with each further axis' travel in turn,
// in axis order (hypot(h, 0) is h exactly, so a path in the plane keeps its
// length bit for bit).
double with_axes_beyond_plane(double plane_mm, const PlanePoint& a, const PlanePoint& b, PlaneAxes plane) noexcept {
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    if (!in_plane(plane, i)) plane_mm = std::hypot(plane_mm, b[i] - a[i]);
  return plane_mm;
}

// |b - a| over every axis.
double distance_mm(const PlanePoint& a, const PlanePoint& b) noexcept {
  const PlaneAxes xy = plane_axes(ArcPlane::xy);
  return with_axes_beyond_plane(std::hypot(b[xy.first] - a[xy.first], b[xy.second] - a[xy.second]), a, b, xy);
}

bool inside(const PlanePoint& p, const MotionLimits& limits, double slack_mm = 0.0) noexcept {
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    if (!(p[i] >= limits.axis[i].position_min_mm - slack_mm && p[i] <= limits.axis[i].position_max_mm + slack_mm))
      return false;
  return true;
}

// An arc's extreme computed from its angle may land a rounding beyond a limit it only touches.
constexpr double kArcExtremeSlack_mm = 1e-9;

// Tangent of an arc at angle theta in its plane; ccw: +90 degrees from the radius vector.
PlanePoint arc_tangent(double theta, bool ccw, PlaneAxes plane) noexcept {
  const double sign = ccw ? 1.0 : -1.0;
  PlanePoint t{};
  t[plane.first] = -sign * std::sin(theta);
  t[plane.second] = sign * std::cos(theta);
  return t;
}

// An arc's extremes on its plane's axes (a G18 arc's Z may rise above both its ends): where its angle passes a multiple
// of 90 degrees (the other axes move linearly: their ends are theirs).
bool arc_inside(const SegmentGeometry& g, const MotionLimits& limits) noexcept {
  constexpr double quarter = 0.5 * std::numbers::pi;
  const double sweep = std::fabs(g.sweep_rad);
  for (int k = 0; k < 4; ++k) {
    double along = g.sweep_rad >= 0.0 ? k * quarter - g.start_angle_rad : g.start_angle_rad - k * quarter;
    along = std::fmod(along, 4.0 * quarter);
    if (along < 0.0) along += 4.0 * quarter;
    if (along <= sweep && !inside(g.arc_point(along / sweep), limits, kArcExtremeSlack_mm)) return false;
  }
  return true;
}

bool known(ArcPlane plane) noexcept { return static_cast<std::uint8_t>(plane) < kArcPlaneCount; }

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
  return arc_point(f);
}

PlanePoint SegmentGeometry::arc_point(double f) const noexcept {
  const double theta = start_angle_rad + f * sweep_rad;
  const double r = start_radius_mm + f * (end_radius_mm - start_radius_mm);
  const PlaneAxes pa = plane_axes(plane);
  PlanePoint p{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) p[i] = start_mm[i] + f * (end_mm[i] - start_mm[i]);
  p[pa.first] = centre_mm[pa.first] + r * std::cos(theta);
  p[pa.second] = centre_mm[pa.second] + r * std::sin(theta);
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
  // A feed per revolution is a plain feed line's.
  if (!std::isfinite(segment.feed_mm_rev)) return SegmentRefusal::not_finite;
  if (segment.feed_mm_rev < 0.0) return SegmentRefusal::feed_not_positive;
  // Along a boring pass's depth: the overhang at the end, and no fixed feed per revolution beside it.
  if (!std::isfinite(segment.overhang_at_end_mm)) return SegmentRefusal::not_finite;
  if (segment.overhang_at_end_mm < 0.0 || (segment.per_rev_along_depth() && segment.feed_mm_rev > 0.0))
    return SegmentRefusal::bad_kind;
  if (segment.per_rev() && (segment.kind != SegmentKind::line || segment.rapid || segment.profiled() ||
                            segment.probe != ProbeKind::none))
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
      if (!known(segment.plane)) return SegmentRefusal::bad_kind;
      const bool ccw = segment.kind == SegmentKind::arc_ccw;
      const PlaneAxes pa = plane_axes(segment.plane);
      const std::size_t a = pa.first;
      const std::size_t b = pa.second;
      const PlanePoint& c = segment.centre_mm;
      g.plane = segment.plane;
      g.centre_mm = c;
      g.end_mm = segment.end_mm;
      g.start_radius_mm = std::hypot(start_mm[a] - c[a], start_mm[b] - c[b]);
      g.end_radius_mm = std::hypot(segment.end_mm[a] - c[a], segment.end_mm[b] - c[b]);
      if (std::fabs(g.start_radius_mm - g.end_radius_mm) > limits.arc_radius_tolerance_mm)
        return SegmentRefusal::arc_radius_mismatch;
      if (g.min_radius_mm() < limits.min_arc_radius_mm) return SegmentRefusal::arc_radius_too_small;
      g.start_angle_rad = std::atan2(start_mm[b] - c[b], start_mm[a] - c[a]);
      const double end_angle = std::atan2(segment.end_mm[b] - c[b], segment.end_mm[a] - c[a]);
      constexpr double two_pi = 2.0 * std::numbers::pi;
      double sweep = end_angle - g.start_angle_rad;
      if (ccw) {
        while (sweep <= 0.0) sweep += two_pi;
      } else {
        while (sweep >= 0.0) sweep -= two_pi;
      }
      // End on the start point in the plane (within the minimum length): a full circle.
      const bool closed = std::hypot(segment.end_mm[a] - start_mm[a], segment.end_mm[b] - start_mm[b]) <
                          limits.min_segment_mm;
      if (closed) sweep = ccw ? two_pi : -two_pi;
      g.sweep_rad = sweep;
      // A helix: the plane's arc length and each further axis' travel, as a line's.
      const double plane_mm = 0.5 * (g.start_radius_mm + g.end_radius_mm) * std::fabs(sweep);
      g.length_mm = with_axes_beyond_plane(plane_mm, start_mm, segment.end_mm, pa);
      if (!(g.length_mm >= limits.min_segment_mm)) return SegmentRefusal::zero_length;
      const double in_plane_share = plane_mm / g.length_mm;
      g.unit_start = arc_tangent(g.start_angle_rad, ccw, pa);
      g.unit_end = arc_tangent(g.start_angle_rad + sweep, ccw, pa);
      for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
        if (in_plane(pa, i)) {
          g.unit_start[i] *= in_plane_share;
          g.unit_end[i] *= in_plane_share;
        } else {
          g.unit_start[i] = g.unit_end[i] = (segment.end_mm[i] - start_mm[i]) / g.length_mm;
        }
      }
      break;
    }
    default: return SegmentRefusal::bad_kind;
  }
  if (!inside(g.end_mm, limits)) return SegmentRefusal::outside_workspace;
  if (g.kind != SegmentKind::line && !arc_inside(g, limits)) return SegmentRefusal::outside_workspace;
  if (!(segment.feed_mm_s > 0.0)) return SegmentRefusal::feed_not_positive;
  if (segment.feed_mm_s > g.axis_speed_cap_mm_s(limits) * (1.0 + 1e-12)) return SegmentRefusal::feed_above_limit;
  if (const SegmentRefusal r = check_ramp(segment, g.length_mm); r != SegmentRefusal::none) return r;
  out = g;
  return SegmentRefusal::none;
}

}  // namespace tnv::fw::motion
