#pragma once
// Tool-side accelerometer code (ADC_ACCEL_X/Y, docs/register-map.md) to
// mm/s^2: offset binary, mid-scale = 0, full scale hal::regs::kAccelFullScaleMmS2.
#include <cstdint>

#include "hal/io_board_registers.hpp"

namespace tnv::fw {

constexpr double accel_code_to_mm_s2(std::uint16_t code) noexcept {
  constexpr double kMid = static_cast<double>(1u << (hal::regs::kAdcBits - 1));
  return (static_cast<double>(code) - kMid) * (hal::regs::kAccelFullScaleMmS2 / kMid);
}

}  // namespace tnv::fw
