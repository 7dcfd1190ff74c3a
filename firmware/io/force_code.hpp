#pragma once
// Force-sensor ADC code (ADC_FORCE, docs/register-map.md: 12-bit unipolar,
// 0..10 V) to newtons with the sensor's scale (force.n_per_volt). The tick's
// force feed-override source and the CAN telemetry read the same number.
#include <cstdint>

#include "hal/io_board_registers.hpp"

namespace tnv::fw {

inline constexpr double kForceAdcFullScaleV = 10.0;

constexpr double force_code_to_n(std::uint16_t code, double n_per_volt) noexcept {
  constexpr double kMaxCode = static_cast<double>((1u << hal::regs::kAdcBits) - 1u);
  return n_per_volt * static_cast<double>(code) * kForceAdcFullScaleV / kMaxCode;
}

}  // namespace tnv::fw
