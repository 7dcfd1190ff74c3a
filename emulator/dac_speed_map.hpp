#pragma once
// Speed DAC code -> commanded table speed (reference plant "Sensors and
// actuators"): offset binary, code 2^(bits-1) = 0 V, 0 = -full scale,
// 2^bits - 1 = +full scale - 1 LSB;
//   u = (code - 2^(bits-1)) / 2^(bits-1) * V_fs * (rpm_fs / V_fs) * lead / 60.
// A real DAC's offset and gain error ([noise] dac_offset_v, dac_gain_error)
// act on the volts: V_out = (1 + gain_error) V_ideal + offset, so
//   u = (code - mid) lsb (1 + gain_error) + offset_v (rpm_fs / V_fs) lead / 60,
// which is the ideal u exactly when both are 0 (x * 1 + 0 == x).
#include <cstdint>

#include "emulator/scenario.hpp"

namespace tnv::emu {

class DacSpeedMap {
 public:
  DacSpeedMap(const DacParams& dac, double lead_mm, double offset_v = 0.0, double gain_error = 0.0) noexcept
      : mid_code_(std::uint32_t{1} << (dac.bits - 1)),
        max_code_((std::uint32_t{1} << dac.bits) - 1),
        // The servopack sees volts; K_v = rpm_fs / V_fs turns them into motor rpm.
        lsb_mm_s_(dac.full_scale_v * (dac.rpm_at_full_scale / dac.full_scale_v) * lead_mm / 60.0 /
                  static_cast<double>(std::uint32_t{1} << (dac.bits - 1))),
        gain_(1.0 + gain_error),
        offset_mm_s_(offset_v * (dac.rpm_at_full_scale / dac.full_scale_v) * lead_mm / 60.0) {}

  std::uint32_t mid_code() const noexcept { return mid_code_; }
  std::uint32_t max_code() const noexcept { return max_code_; }
  double lsb_mm_s() const noexcept { return lsb_mm_s_; }
  // Valid codes only (0..max_code); the board refuses others.
  double speed_mm_s(std::uint32_t code) const noexcept {
    return (static_cast<double>(code) - static_cast<double>(mid_code_)) * lsb_mm_s_ * gain_ + offset_mm_s_;
  }

 private:
  std::uint32_t mid_code_;
  std::uint32_t max_code_;
  double lsb_mm_s_;
  double gain_;         // 1 + gain error
  double offset_mm_s_;  // the offset volts as table speed
};

}  // namespace tnv::emu
