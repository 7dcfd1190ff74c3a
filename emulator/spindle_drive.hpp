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
#include <cstddef>
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
  // The drive's inputs as the board's outputs give them: the DAC's code, the
  // enable and the direction input. Enabled, it follows the code when the
  // direction input agrees with the code's sign (0 V agrees with both);
  // disabled or disagreeing, its command is 0 rpm and the spec's law brings
  // it to rest (as a disabled axis' servopack gets 0 V).
  void set_inputs(std::uint32_t code, bool enabled, bool reverse) noexcept;

  // One 10 us sub-step under cutting load cutting_force_n (newtons, >= 0).
  void step(double cutting_force_n = 0.0) noexcept;
  // `count` (<= AxisPlant::kMaxBlock) sub-steps with the command held and no
  // load: the machine's block. Nothing to do at rest; with no command, a
  // speed below kRestRpm ends at rest with the exponential's remaining
  // travel (n tau_sp) added, so an idle spindle stops being integrated.
  void advance_unloaded(std::size_t count) noexcept;
  // After sub-steps of step(): with no command, a speed below kRestRpm ends
  // at rest as advance_unloaded() ends it.
  void settle_if_stopping() noexcept;
  bool at_rest() const noexcept { return commanded_rpm_ == 0.0 && motor_.speed_mm_s() == 0.0; }
  static constexpr double kRestRpm = 1e-3;  // its remaining travel: 3e-6 rev, 0.014 counts

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
  void settle(AxisState& s) const noexcept;
};

}  // namespace tnv::emu
