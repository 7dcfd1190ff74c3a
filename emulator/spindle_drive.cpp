#include "emulator/spindle_drive.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::emu {

namespace {

AxisPlantParams motor_law(const SpindleParams& p) noexcept {
  // gain 1: the command is already in rpm; friction off: the drive's speed
  // loop absorbs the spindle's bearing drag (the spec has no friction term).
  return AxisPlantParams{.tau_s = p.tau_s,
                         .gain = 1.0,
                         .coulomb_mm_s = 0.0,
                         .stiction_mm_s = 0.0,
                         .stribeck_mm_s = 1.0,
                         .accel_limit_mm_s2 = p.accel_limit_rpm_s};
}

}  // namespace

SpindleDrive::SpindleDrive(const SpindleParams& params) noexcept
    : params_(params),
      motor_(motor_law(params)),
      mid_code_(std::uint32_t{1} << (params.dac_bits - 1)),
      max_code_((std::uint32_t{1} << params.dac_bits) - 1),
      // Volts per code times K_sp = rpm_at_full_scale / full_scale_v.
      rpm_per_code_(params.full_scale_v / static_cast<double>(std::uint32_t{1} << (params.dac_bits - 1)) *
                    (params.rpm_at_full_scale / params.full_scale_v)) {}

void SpindleDrive::set_command_code(std::uint32_t code) noexcept {
  code = std::min(code, max_code_);
  commanded_rpm_ = (static_cast<double>(code) - static_cast<double>(mid_code_)) * rpm_per_code_;
}

void SpindleDrive::set_inputs(std::uint32_t code, bool enabled, bool reverse) noexcept {
  set_command_code(code);
  const bool agrees = commanded_rpm_ == 0.0 || (commanded_rpm_ < 0.0) == reverse;
  if (!enabled || !agrees) commanded_rpm_ = 0.0;
}

std::uint32_t SpindleDrive::code_for_rpm(double rpm) const noexcept {
  const double code = std::round(rpm / rpm_per_code_) + static_cast<double>(mid_code_);
  return static_cast<std::uint32_t>(std::clamp(code, 0.0, static_cast<double>(max_code_)));
}

void SpindleDrive::step(double cutting_force_n) noexcept {
  const double n = motor_.speed_mm_s();
  const double direction = n != 0.0 ? std::copysign(1.0, n) : commanded_rpm_ != 0.0 ? std::copysign(1.0, commanded_rpm_) : 0.0;
  motor_.step(commanded_rpm_, -direction * params_.droop_rpm_per_n * std::max(cutting_force_n, 0.0));
}

void SpindleDrive::advance_unloaded(std::size_t count) noexcept {
  if (at_rest()) return;
  AxisState s = motor_.state();
  motor_.advance_held(s, commanded_rpm_, 0.0, count);
  settle(s);
  motor_.set_state(s);
}

// Below the limit's knee (A tau) the law is v' = -v / tau: the rest of the
// way to zero is v tau exactly.
void SpindleDrive::settle(AxisState& s) const noexcept {
  if (commanded_rpm_ == 0.0 && std::abs(s.speed_mm_s) < kRestRpm) {
    s.position_mm += s.speed_mm_s * params_.tau_s;
    s.speed_mm_s = 0.0;
  }
}

void SpindleDrive::settle_if_stopping() noexcept {
  if (at_rest()) return;
  AxisState s = motor_.state();
  settle(s);
  motor_.set_state(s);
}

}  // namespace tnv::emu
