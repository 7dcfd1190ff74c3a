#pragma once
// M-method speed: counted pulses over the MEASURED period between two tick
// latches of the 10 MHz counter (not an assumed 1 ms), so a jittered or
// late tick does not bias the speed (S1 hardware; design notes "The tick").
#include <cstdint>

#include "hal/timebase.hpp"

namespace tnv::fw {

// Clocks between two latched counter values; unsigned arithmetic makes the
// 32-bit wrap (every 429 s) invisible.
constexpr std::uint32_t elapsed_clocks(std::uint32_t earlier, std::uint32_t later) noexcept {
  return later - earlier;
}

// v = delta_count * q / period. period_clocks == 0 yields 0 (caller faults on it).
constexpr double m_method_speed_mm_s(std::int64_t delta_counts, double count_mm,
                                     std::uint32_t period_clocks) noexcept {
  if (period_clocks == 0) return 0.0;
  const double period_s = static_cast<double>(period_clocks) / static_cast<double>(hal::kTimebaseHz);
  return static_cast<double>(delta_counts) * count_mm / period_s;
}

}  // namespace tnv::fw
