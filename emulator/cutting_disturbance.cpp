#include "emulator/cutting_disturbance.hpp"

#include <numbers>

#include "emulator/substep_timing.hpp"

namespace tnv::emu {

CuttingDisturbance::CuttingDisturbance(const CuttingParams& cutting, const CircleParams& circle) noexcept
    : enabled_(cutting.enabled),
      frequency_hz_(cutting.flutes * cutting.spindle_rpm / 60.0),
      phase_rad_(cutting.phase_rad),
      mean_mm_s_(cutting.mean_mm_s),
      amplitude_mm_s_(cutting.amplitude_mm_s),
      // reference plant: chip thickness ~ 1/S, Kienzle exponent on (900/S)
      gain_per_feed_(std::pow(900.0 / cutting.spindle_rpm, cutting.exponent) / circle.feed_mm_s),
      tooth_powers_(phasor_powers<kMaxFill>(2.0 * std::numbers::pi * frequency_hz_ * kSubstep_s)),
      path_(circle) {}

Phasor CuttingDisturbance::tooth_phase(std::uint64_t substep) const noexcept {
  // Whole tooth periods dropped before scaling by 2 pi keeps the phase
  // accurate late in long runs.
  const double cycles = frequency_hz_ * substep_time_s(substep);
  return Phasor::at(2.0 * std::numbers::pi * (cycles - std::floor(cycles)) + phase_rad_);
}

}  // namespace tnv::emu
