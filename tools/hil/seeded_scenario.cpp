#include "tools/hil/seeded_scenario.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>

namespace tnv::hil {

namespace {
// Additive recurrence with the plastic-number generalisation of the golden
// ratio: well spread in 3-D (x offset, y offset, phase) for any N.
constexpr double kG = 1.32471795724474602596;
constexpr double kA1 = 1.0 / kG;
constexpr double kA2 = 1.0 / (kG * kG);
constexpr double kA3 = 1.0 / (kG * kG * kG);

double frac(double v) noexcept { return v - std::floor(v); }
}  // namespace

emu::Scenario seeded(const emu::Scenario& base, int seed) noexcept {
  emu::Scenario s = base;
  if (seed == 0) return s;
  const double k = static_cast<double>(seed);
  s.encoder.axis_offset_counts[0] = base.encoder.axis_offset_counts[0] + frac(k * kA1);
  s.encoder.axis_offset_counts[1] = base.encoder.axis_offset_counts[1] + frac(k * kA2);
  s.cutting.phase_rad = base.cutting.phase_rad + 2.0 * std::numbers::pi * frac(k * kA3);
  // A new noise and jitter realisation per seed (inert while [noise] and [io] are off).
  s.noise.seed = base.noise.seed + static_cast<std::uint32_t>(seed);
  return s;
}

}  // namespace tnv::hil
