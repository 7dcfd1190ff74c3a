#include "tools/gcode/path_distance.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tnv::gcode {

using fw::motion::PlanePoint;
using fw::motion::SegmentGeometry;
using fw::motion::SegmentKind;

namespace {

// Over every axis: the plane's two first, then each further one (hypot(h, 0) is h exactly).
double point_distance_mm(const PlanePoint& a, const PlanePoint& b) noexcept {
  double d = std::hypot(a[0] - b[0], a[1] - b[1]);
  for (std::size_t i = 2; i < a.size(); ++i) d = std::hypot(d, a[i] - b[i]);
  return d;
}

}  // namespace

double distance_to_segment_mm(const SegmentGeometry& g, const PlanePoint& p) noexcept {
  switch (g.kind) {
    case SegmentKind::dwell: return point_distance_mm(g.start_mm, p);
    case SegmentKind::line: {
      double len2 = 0.0, dot = 0.0;
      for (std::size_t i = 0; i < p.size(); ++i) {
        const double d = g.end_mm[i] - g.start_mm[i];
        len2 += d * d;
        dot += (p[i] - g.start_mm[i]) * d;
      }
      const double t = len2 > 0.0 ? std::clamp(dot / len2, 0.0, 1.0) : 0.0;
      PlanePoint q{};
      for (std::size_t i = 0; i < p.size(); ++i) q[i] = g.start_mm[i] + t * (g.end_mm[i] - g.start_mm[i]);
      return point_distance_mm(q, p);
    }
    case SegmentKind::arc_cw:
    case SegmentKind::arc_ccw: {
      constexpr double two_pi = 2.0 * std::numbers::pi;
      const fw::motion::PlaneAxes pa = fw::motion::plane_axes(g.plane);
      const std::size_t a = pa.first, b = pa.second;
      const double angle = std::atan2(p[b] - g.centre_mm[b], p[a] - g.centre_mm[a]);
      // Angle travelled from the start in the arc's own direction, in [0, 2 pi).
      double along = g.sweep_rad >= 0.0 ? angle - g.start_angle_rad : g.start_angle_rad - angle;
      along = std::fmod(along, two_pi);
      if (along < 0.0) along += two_pi;
      const double sweep = std::fabs(g.sweep_rad);
      if (along <= sweep) {
        // The radius moves linearly from start to end (within the arc tolerance).
        const double f = along / sweep;
        const double r = g.start_radius_mm + (g.end_radius_mm - g.start_radius_mm) * f;
        // A helix: the other axes at that angle (an upper bound on the distance, within the pitch's slope).
        double d = std::fabs(std::hypot(p[a] - g.centre_mm[a], p[b] - g.centre_mm[b]) - r);
        for (std::size_t i = 0; i < p.size(); ++i)
          if (!fw::motion::in_plane(pa, i)) d = std::hypot(d, p[i] - (g.start_mm[i] + f * (g.end_mm[i] - g.start_mm[i])));
        return d;
      }
      return std::min(point_distance_mm(g.start_mm, p), point_distance_mm(g.end_mm, p));
    }
  }
  return point_distance_mm(g.start_mm, p);
}

ProgrammedPath::ProgrammedPath(std::vector<SegmentGeometry> elements) {
  for (SegmentGeometry& g : elements) {
    if (g.kind == SegmentKind::dwell) continue;
    for (std::size_t i = 2; i < g.start_mm.size(); ++i) plane_only_ = plane_only_ && g.end_mm[i] == g.start_mm[i];
    // An arc in G18 or G19 moves Z between its ends.
    if (g.kind != SegmentKind::line && g.plane != fw::motion::ArcPlane::xy) plane_only_ = false;
    elements_.push_back(g);
  }
}

double ProgrammedPath::distance_mm(const PlanePoint& point) const noexcept {
  PlanePoint p = point;
  if (plane_only_ && !elements_.empty())  // measured in the plane: the other axes held are not the path's
    for (std::size_t i = 2; i < p.size(); ++i) p[i] = elements_.front().start_mm[i];
  double best = 1e300;
  for (const SegmentGeometry& g : elements_) {
    if (g.kind == SegmentKind::arc_cw || g.kind == SegmentKind::arc_ccw) {
      // No point of the arc is nearer than the band between its radii: skip the angle test.
      const fw::motion::PlaneAxes pa = fw::motion::plane_axes(g.plane);
      const double from_centre = std::hypot(p[pa.first] - g.centre_mm[pa.first], p[pa.second] - g.centre_mm[pa.second]);
      const double r_lo = std::min(g.start_radius_mm, g.end_radius_mm);
      const double r_hi = std::max(g.start_radius_mm, g.end_radius_mm);
      const double band = from_centre < r_lo ? r_lo - from_centre : from_centre > r_hi ? from_centre - r_hi : 0.0;
      if (band >= best) continue;
    }
    best = std::min(best, distance_to_segment_mm(g, p));
  }
  return best;
}

}  // namespace tnv::gcode
