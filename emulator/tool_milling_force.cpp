#include "emulator/tool_milling_force.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::emu {

namespace {
constexpr double kKienzleExponent = 0.75;  // on f_z (S3)
constexpr double kDiameterExponent = 0.25;  // on D (S3)
}  // namespace

double specific_cutting_force_n_mm2(double force_n, double depth_mm, double feed_per_tooth_mm, double diameter_mm) {
  return force_n / (depth_mm * std::pow(feed_per_tooth_mm, kKienzleExponent) * std::pow(diameter_mm, kDiameterExponent));
}

ToolMillingForce::ToolMillingForce(const ToolCutParams& cut, const ToolParams& tool, double substep_s) noexcept
    : cut_(cut),
      tool_(tool),
      diameter_term_(std::pow(tool.diameter_mm, kDiameterExponent)),
      decay_(std::exp(-substep_s / cut.time_constant_s)) {}

double ToolMillingForce::feed_per_tooth_mm(double speed_xy_mm_s, double spindle_rpm) const noexcept {
  if (speed_xy_mm_s <= 0.0) return 0.0;
  const double teeth_per_s = tool_.flutes * std::abs(spindle_rpm) / 60.0;
  if (!(teeth_per_s > 0.0)) return cut_.max_feed_per_tooth_mm;
  return std::min(speed_xy_mm_s / teeth_per_s, cut_.max_feed_per_tooth_mm);
}

double ToolMillingForce::steady_force_n(double depth_mm, double feed_per_tooth_mm) const noexcept {
  if (depth_mm <= 0.0 || feed_per_tooth_mm <= 0.0) return 0.0;
  return cut_.k_c_n_mm2 * depth_mm * std::pow(feed_per_tooth_mm, kKienzleExponent) * diameter_term_;
}

void ToolMillingForce::advance(double vx_mm_s, double vy_mm_s, double depth_mm, double spindle_rpm) noexcept {
  const double speed_mm_s = std::hypot(vx_mm_s, vy_mm_s);
  double target_x_n = 0.0, target_y_n = 0.0;
  if (speed_mm_s > 0.0) {
    const double f_n = steady_force_n(depth_mm, feed_per_tooth_mm(speed_mm_s, spindle_rpm));
    target_x_n = -f_n * vx_mm_s / speed_mm_s;
    target_y_n = -f_n * vy_mm_s / speed_mm_s;
  }
  // Exact for inputs held over the sub-step (as milling_force.cpp).
  force_x_n_ = decay_ * force_x_n_ + (1.0 - decay_) * target_x_n;
  force_y_n_ = decay_ * force_y_n_ + (1.0 - decay_) * target_y_n;
}

double ToolMillingForce::force_n() const noexcept { return std::hypot(force_x_n_, force_y_n_); }

}  // namespace tnv::emu
