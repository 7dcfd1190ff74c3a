#pragma once
// Distance from a point to the nearest point of the programmed lines and
// arcs (not to a radius): the measure behind contour_error (measured
// position) and path_deviation (the planner's own reference). In every axis
// the program moves: a program that keeps Z is measured in the XY plane (Z
// holding is its own axis' business, and the plane's numbers stay as they
// were), one that moves Z in three dimensions.
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
  bool plane_only() const noexcept { return plane_only_; }  // no element moves an axis beyond X and Y
  std::size_t size() const noexcept { return elements_.size(); }

 private:
  std::vector<fw::motion::SegmentGeometry> elements_;
  bool plane_only_ = true;
};

}  // namespace tnv::gcode
