#pragma once
// x4-decoded quadrature encoder on the table (reference plant "Sensors"):
// count = round(p / q + offset_counts), q = lead_mm / counts_per_rev, read
// through a kEncoderBits-wide wrapping register. Measures the table position
// p, not the tool point.
#include <cmath>
#include <cstdint>

#include "hal/io_board_registers.hpp"

namespace tnv::emu {

class QuadratureEncoder {
 public:
  QuadratureEncoder(double count_mm, double offset_counts) noexcept
      : count_mm_(count_mm), offset_counts_(offset_counts) {}

  double count_mm() const noexcept { return count_mm_; }

  // Unbounded count (round half away from zero).
  std::int64_t count(double position_mm) const noexcept {
    return std::llround(position_mm / count_mm_ + offset_counts_);
  }
  // What the board's counter register holds: two's complement modulo 2^kEncoderBits.
  std::uint32_t register_value(double position_mm) const noexcept { return wrap(count(position_mm)); }

  static constexpr std::uint32_t wrap(std::int64_t count) noexcept {
    constexpr std::uint64_t kMask = (std::uint64_t{1} << hal::regs::kEncoderBits) - 1;
    return static_cast<std::uint32_t>(static_cast<std::uint64_t>(count) & kMask);
  }

 private:
  double count_mm_;
  double offset_counts_;
};

}  // namespace tnv::emu
