#pragma once
// Force-sensor channel of the board ADC: unipolar 0..10 V, kAdcBits wide,
// reading the magnitude of the 2-D cutting disturbance.
//   code = clamp(round(|d_cut| volts_per_mm_s / 10 V * (2^bits - 1)), 0, 2^bits - 1)
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "hal/io_board_registers.hpp"

namespace tnv::emu {

inline constexpr double kAdcFullScaleV = 10.0;

// The code for `volts` at the ADC's input (noise included, if any): below 0 V reads 0.
inline std::uint32_t force_adc_code_for_volts(double volts) noexcept {
  constexpr double kMaxCode = static_cast<double>((1u << hal::regs::kAdcBits) - 1);
  const double code = std::round(volts / kAdcFullScaleV * kMaxCode);
  if (!(code > 0.0)) return 0;  // also NaN
  return static_cast<std::uint32_t>(std::min(code, kMaxCode));
}

inline std::uint32_t force_adc_code(double magnitude_mm_s, double volts_per_mm_s) noexcept {
  return force_adc_code_for_volts(magnitude_mm_s * volts_per_mm_s);
}

}  // namespace tnv::emu
