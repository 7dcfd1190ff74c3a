#pragma once
// Extends a fixed-width wrapping quadrature counter to an unbounded count
// by taking signed differences between ticks. Correct as long as the axis
// moves less than half the counter range per tick (16 bits: 13.6 m/s).
#include <cstdint>

namespace tnv::fw {

class EncoderPosition {
 public:
  // counter_bits: width of the hardware counter (1..32).
  explicit EncoderPosition(unsigned counter_bits = 16) noexcept
      : mask_(counter_bits >= 32 ? 0xFFFFFFFFu : ((1u << counter_bits) - 1u)),
        sign_bit_(1u << ((counter_bits >= 32 ? 32u : counter_bits) - 1u)) {}

  // First reading after power-up / homing: the extended count starts at 0.
  void reset(std::uint32_t raw) noexcept {
    last_raw_ = raw & mask_;
    extended_counts_ = 0;
  }

  // Returns the count change since the previous reading (sign-extended).
  std::int64_t update(std::uint32_t raw) noexcept {
    const std::int64_t delta = since_last(raw);
    last_raw_ = raw & mask_;
    extended_counts_ += delta;
    return delta;
  }

  std::int64_t counts() const noexcept { return extended_counts_; }

  // The extended count of another reading of the same counter within half
  // its range of the last one (a count the board latched at an index edge).
  std::int64_t counts_at(std::uint32_t raw) const noexcept { return extended_counts_ + since_last(raw); }

 private:
  std::int64_t since_last(std::uint32_t raw) const noexcept {
    const std::uint32_t diff = (raw - last_raw_) & mask_;
    return (diff & sign_bit_) ? static_cast<std::int64_t>(diff) - static_cast<std::int64_t>(mask_) - 1
                              : static_cast<std::int64_t>(diff);
  }

  std::uint32_t mask_;
  std::uint32_t sign_bit_;
  std::uint32_t last_raw_ = 0;
  std::int64_t extended_counts_ = 0;
};

}  // namespace tnv::fw
