#pragma once
// The spindle drive and motor (reference plant "Spindle"), in rpm:
//   tau_sp dn/dt = K_sp u_sp - n - k_d F_cut,   |dn/dt| <= a_sp.
// This is the axis plant's current-limited law (axis_plant.hpp) with rpm in
// place of mm/s and no friction, so it is stepped by an AxisPlant: its
// "position" is the integral of n, rpm*s, i.e. 60 times the revolutions.
// The command arrives as a code of the spindle's own speed DAC (offset
// binary like the axes' DACs; +full scale = +rpm_at_full_scale, the sign
// is the direction). The load opposes the rotation: the droop is
// k_d F_cut toward zero speed (the spec's -k_d F_cut for n > 0).
#include <cstdint>

#include "emulator/axis_plant.hpp"
#include "emulator/scenario.hpp"

namespace tnv::emu {

class SpindleDrive {
 public:
  explicit SpindleDrive(const SpindleParams& params) noexcept;

  std::uint32_t mid_code() const noexcept { return mid_code_; }
  std::uint32_t max_code() const noexcept { return max_code_; }
  double rpm_per_code() const noexcept { return rpm_per_code_; }
  // The speed DAC's code -> commanded speed; codes beyond max_code saturate.
  void set_command_code(std::uint32_t code) noexcept;
  // The nearest code to a speed, saturated (what a controller would write).
  std::uint32_t code_for_rpm(double rpm) const noexcept;
  double commanded_rpm() const noexcept { return commanded_rpm_; }

  // One 10 us sub-step under cutting load cutting_force_n (newtons, >= 0).
  void step(double cutting_force_n = 0.0) noexcept;

  double speed_rpm() const noexcept { return motor_.speed_mm_s(); }
  double revolutions() const noexcept { return motor_.position_mm() / 60.0; }
  const SpindleParams& params() const noexcept { return params_; }

 private:
  SpindleParams params_;
  AxisPlant motor_;  // rpm for mm/s, rpm*s for mm
  std::uint32_t mid_code_;
  std::uint32_t max_code_;
  double rpm_per_code_;
  double commanded_rpm_ = 0.0;
};

}  // namespace tnv::emu
