#include "emulator/cutting_disturbance.hpp"

#include <numbers>

#include "emulator/substep_timing.hpp"

namespace tnv::emu {

namespace {
// reference plant: chip thickness ~ feed / S, Kienzle exponent on (900/S);
// normalised so the mean load at the programmed feed F is c_m.
double load_scale_per_speed(const CuttingParams& cutting, double programmed_feed_mm_s) noexcept {
  return std::pow(900.0 / cutting.spindle_rpm, cutting.exponent) / programmed_feed_mm_s;
}
}  // namespace

CuttingDisturbance::CuttingDisturbance(const CuttingParams& cutting, double programmed_feed_mm_s) noexcept
    : enabled_(cutting.enabled),
      frequency_hz_(cutting.flutes * cutting.spindle_rpm / 60.0),
      phase_rad_(cutting.phase_rad),
      mean_per_speed_(load_scale_per_speed(cutting, programmed_feed_mm_s) * cutting.mean_mm_s),
      amplitude_per_speed_(load_scale_per_speed(cutting, programmed_feed_mm_s) * cutting.amplitude_mm_s),
      tooth_powers_(phasor_powers<kMaxFill>(2.0 * std::numbers::pi * frequency_hz_ * kSubstep_s)) {}

Phasor CuttingDisturbance::tooth_phase(std::uint64_t substep) const noexcept {
  // Whole tooth periods dropped before scaling by 2 pi keeps the phase
  // accurate late in long runs.
  const double cycles = frequency_hz_ * substep_time_s(substep);
  return Phasor::at(2.0 * std::numbers::pi * (cycles - std::floor(cycles)) + phase_rad_);
}

}  // namespace tnv::emu
