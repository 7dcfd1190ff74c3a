#pragma once
// The milling force where the tool is (reference plant "Stock, and cutting
// where the tool is"), for any path:
//   f_z  = |v_xy| / (N |n| / 60)                     feed per tooth, mm
//   F_ss = K_c a_p f_z^0.75 D^0.25                   newtons (S3's process)
//   T_f dF/dt = F_ss_vec - F,   F_ss_vec = -F_ss v_xy / |v_xy|
// i.e. the force opposes the XY feed and follows it through S3's
// first-order lag, integrated exactly over each 10 us sub-step with the
// inputs held (the lag acts on the force vector, so a change of feed
// direction turns the force over T_f, as a change of depth does). Each XY
// axis sees F / stiffness as a table-speed disturbance. f_z is capped at
// max_feed_per_tooth_mm: with a stopped spindle it would be infinite, and
// that case is a crash (spindle_crash_log.hpp), not a cut.
#include "emulator/scenario.hpp"

namespace tnv::emu {

class ToolMillingForce {
 public:
  ToolMillingForce(const ToolCutParams& cut, const ToolParams& tool, double substep_s) noexcept;

  // f_z from the table's XY speed and the spindle's actual speed (capped).
  double feed_per_tooth_mm(double speed_xy_mm_s, double spindle_rpm) const noexcept;
  // F_ss at a_p and f_z.
  double steady_force_n(double depth_mm, double feed_per_tooth_mm) const noexcept;

  // One sub-step: table XY speed, axial engagement a_p, actual spindle speed.
  void advance(double vx_mm_s, double vy_mm_s, double depth_mm, double spindle_rpm) noexcept;

  double force_x_n() const noexcept { return force_x_n_; }
  double force_y_n() const noexcept { return force_y_n_; }
  double force_n() const noexcept;  // |F|, the spindle's load
  double disturbance_x_mm_s() const noexcept { return force_x_n_ / cut_.stiffness_n_per_mm_s; }
  double disturbance_y_mm_s() const noexcept { return force_y_n_ / cut_.stiffness_n_per_mm_s; }

 private:
  ToolCutParams cut_;
  ToolParams tool_;
  double diameter_term_;  // D^0.25
  double decay_;          // exp(-h / T_f)
  double force_x_n_ = 0.0;
  double force_y_n_ = 0.0;
};

}  // namespace tnv::emu
