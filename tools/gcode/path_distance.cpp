#include "tools/gcode/path_distance.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tnv::gcode {

using fw::motion::PlanePoint;
using fw::motion::SegmentGeometry;
using fw::motion::SegmentKind;

namespace {

double point_distance_mm(const PlanePoint& a, const PlanePoint& b) noexcept {
  return std::hypot(a[0] - b[0], a[1] - b[1]);
}

}  // namespace

double distance_to_segment_mm(const SegmentGeometry& g, const PlanePoint& p) noexcept {
  switch (g.kind) {
    case SegmentKind::dwell: return point_distance_mm(g.start_mm, p);
    case SegmentKind::line: {
      const double dx = g.end_mm[0] - g.start_mm[0], dy = g.end_mm[1] - g.start_mm[1];
      const double len2 = dx * dx + dy * dy;
      const double t =
          len2 > 0.0 ? std::clamp(((p[0] - g.start_mm[0]) * dx + (p[1] - g.start_mm[1]) * dy) / len2, 0.0, 1.0) : 0.0;
      return std::hypot(p[0] - g.start_mm[0] - t * dx, p[1] - g.start_mm[1] - t * dy);
    }
    case SegmentKind::arc_cw:
    case SegmentKind::arc_ccw: {
      constexpr double two_pi = 2.0 * std::numbers::pi;
      const double angle = std::atan2(p[1] - g.centre_mm[1], p[0] - g.centre_mm[0]);
      // Angle travelled from the start in the arc's own direction, in [0, 2 pi).
      double along = g.sweep_rad >= 0.0 ? angle - g.start_angle_rad : g.start_angle_rad - angle;
      along = std::fmod(along, two_pi);
      if (along < 0.0) along += two_pi;
      const double sweep = std::fabs(g.sweep_rad);
      if (along <= sweep) {
        // The radius moves linearly from start to end (within the arc tolerance).
        const double r = g.start_radius_mm + (g.end_radius_mm - g.start_radius_mm) * along / sweep;
        return std::fabs(std::hypot(p[0] - g.centre_mm[0], p[1] - g.centre_mm[1]) - r);
      }
      return std::min(point_distance_mm(g.start_mm, p), point_distance_mm(g.end_mm, p));
    }
  }
  return point_distance_mm(g.start_mm, p);
}

ProgrammedPath::ProgrammedPath(std::vector<SegmentGeometry> elements) {
  for (SegmentGeometry& g : elements)
    if (g.kind != SegmentKind::dwell) elements_.push_back(g);
}

double ProgrammedPath::distance_mm(const PlanePoint& p) const noexcept {
  double best = 1e300;
  for (const SegmentGeometry& g : elements_) {
    if (g.kind == SegmentKind::arc_cw || g.kind == SegmentKind::arc_ccw) {
      // No point of the arc is nearer than the band between its radii: skip the angle test.
      const double from_centre = std::hypot(p[0] - g.centre_mm[0], p[1] - g.centre_mm[1]);
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
