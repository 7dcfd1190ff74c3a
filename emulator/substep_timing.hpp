#pragma once
// The emulator's one time grid: the 10 MHz board clock and the 10 us
// physics sub-step (reference plant: "fixed sub-steps of h = 10 us").
#include <cstdint>

namespace tnv::emu {

inline constexpr std::uint64_t kClockHz = 10'000'000;
inline constexpr std::uint64_t kSubstepClocks = 100;
inline constexpr std::uint64_t kSubstepsPerSecond = kClockHz / kSubstepClocks;
inline constexpr double kSubstep_s = 1.0 / static_cast<double>(kSubstepsPerSecond);

// Time of sub-step boundary k: a product (cheap in the per-sub-step path)
// rather than a running sum, so time never drifts; within 2e-16 relative
// of k / 100000.
constexpr double substep_time_s(std::uint64_t substep) noexcept {
  return static_cast<double>(substep) * kSubstep_s;
}

}  // namespace tnv::emu
