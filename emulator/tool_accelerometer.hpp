#pragma once
// Tool-side accelerometer per axis (docs/register-map.md, ADC_ACCEL_X/Y):
// the acceleration of the tool point, i.e. the table's plus the structural
// mode's deflection x_d'', sampled at the tick latch, quantised to the board
// ADC and saturated at +-hal::regs::kAccelFullScaleMmS2. Without a mode the
// tool point is the table, and it reads the table's acceleration.
//   code = clamp(round(mid + a / full_scale * mid), 0, 2^bits - 1),  mid = 2^(bits-1)
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "emulator/axis_plant.hpp"
#include "hal/io_board_registers.hpp"

namespace tnv::emu {

inline std::uint32_t accel_adc_code(double accel_mm_s2) noexcept {
  constexpr double kMid = static_cast<double>(1u << (hal::regs::kAdcBits - 1));
  constexpr double kMaxCode = static_cast<double>((1u << hal::regs::kAdcBits) - 1);
  const double code = std::round(kMid + accel_mm_s2 / hal::regs::kAccelFullScaleMmS2 * kMid);
  if (!(code > 0.0)) return 0;  // also NaN
  return static_cast<std::uint32_t>(std::min(code, kMaxCode));
}

// Table acceleration now, from the axis law tau dv/dt = K u + d - f(v) - v
// (reference plant "Axis") with the sub-step's held inputs: 0 while
// stiction holds the axis, the break-away law at v == 0 otherwise, and
// within +-accel_limit_mm_s2 when the plant has one. (The motor side's: with
// backlash the table itself stands still while the lash is taken up.)
inline double table_acceleration_mm_s2(const AxisPlant& plant, double command_mm_s, double disturbance_mm_s) noexcept {
  const double limit_mm_s2 = plant.accel_limit_mm_s2();
  const auto limited = [limit_mm_s2](double accel_mm_s2) {
    return limit_mm_s2 > 0.0 ? std::clamp(accel_mm_s2, -limit_mm_s2, limit_mm_s2) : accel_mm_s2;
  };
  const double drive_mm_s = plant.gain() * command_mm_s + disturbance_mm_s;
  const double v_mm_s = plant.speed_mm_s();
  if (!plant.friction_enabled()) return limited((drive_mm_s - v_mm_s) / plant.tau_s());
  if (v_mm_s == 0.0) {
    const double fs_mm_s = plant.friction().stiction_mm_s();
    if (std::abs(drive_mm_s) <= fs_mm_s) return 0.0;  // Karnopp: held
    return limited((drive_mm_s - std::copysign(fs_mm_s, drive_mm_s)) / plant.tau_s());
  }
  const double friction_mm_s = std::copysign(plant.friction().magnitude_mm_s(v_mm_s), v_mm_s);
  return limited((drive_mm_s - friction_mm_s - v_mm_s) / plant.tau_s());
}

}  // namespace tnv::emu
