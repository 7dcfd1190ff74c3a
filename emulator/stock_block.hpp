#pragma once
// The block of stock (reference plant "Stock"): top face at z_top, sides on
// an XY rectangle (unbounded by default: the whole table), reaching down to
// the table. Answers where a tool point is relative to it; knows nothing
// of forces.
#include <algorithm>
#include <cmath>

#include "emulator/scenario.hpp"

namespace tnv::emu {

class StockBlock {
 public:
  explicit StockBlock(const StockParams& params) noexcept : p_(params) {}

  double top_mm() const noexcept { return p_.top_mm; }

  // Distance in XY from (x, y) to the rectangle (0 on or inside it).
  double xy_distance_mm(double x_mm, double y_mm) const noexcept {
    const double dx = std::max({p_.x_min_mm - x_mm, 0.0, x_mm - p_.x_max_mm});
    const double dy = std::max({p_.y_min_mm - y_mm, 0.0, y_mm - p_.y_max_mm});
    return std::hypot(dx, dy);
  }
  // Distance from a point to the solid (0 on a face or inside).
  double distance_mm(double x_mm, double y_mm, double z_mm) const noexcept {
    return std::hypot(xy_distance_mm(x_mm, y_mm), std::max(z_mm - p_.top_mm, 0.0));
  }
  // Axial engagement of an end mill whose tool point is at (x, y, z):
  // a_p = clamp(z_top - z, 0, flute length) while its disc overlaps the
  // rectangle (centre closer than D/2 to it), else 0.
  double engagement_mm(double x_mm, double y_mm, double z_mm, const ToolParams& tool) const noexcept {
    if (!(xy_distance_mm(x_mm, y_mm) < 0.5 * tool.diameter_mm)) return 0.0;
    return std::clamp(p_.top_mm - z_mm, 0.0, tool.flute_length_mm);
  }

 private:
  StockParams p_;
};

}  // namespace tnv::emu
