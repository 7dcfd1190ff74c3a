#pragma once
// Distance from a point to the nearest point of the programmed lines and
// arcs (not to a radius): the measure behind contour_error (measured
// position) and path_deviation (the planner's own reference).
#include <cstddef>
#include <vector>

#include "firmware/motion/segment_geometry.hpp"

namespace tnv::gcode {

double distance_to_segment_mm(const fw::motion::SegmentGeometry& g, const fw::motion::PlanePoint& p) noexcept;

class ProgrammedPath {
 public:
  explicit ProgrammedPath(std::vector<fw::motion::SegmentGeometry> elements);
  // Nearest over every line and arc (dwells have no extent and are skipped).
  double distance_mm(const fw::motion::PlanePoint& p) const noexcept;
  std::size_t size() const noexcept { return elements_.size(); }

 private:
  std::vector<fw::motion::SegmentGeometry> elements_;
};

}  // namespace tnv::gcode
