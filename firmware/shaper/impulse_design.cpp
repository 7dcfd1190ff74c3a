#include "firmware/shaper/impulse_design.hpp"

#include <cmath>
#include <numbers>

namespace tnv::fw {

ParamCheck validate(const ModeSpec& mode) noexcept {
  if (!std::isfinite(mode.freq_hz) || mode.freq_hz < kShaperMinFreqHz || mode.freq_hz > kShaperMaxFreqHz)
    return param_error("freq_hz", "must be finite, 5..200 Hz");
  if (!std::isfinite(mode.zeta) || mode.zeta < 0.0 || mode.zeta > kShaperMaxZeta)
    return param_error("zeta", "must be finite, 0..0.3");
  return param_ok();
}

double damped_period_s(const ModeSpec& mode) noexcept {
  return 1.0 / (mode.freq_hz * std::sqrt(1.0 - mode.zeta * mode.zeta));
}

int design_multiplicity(ShaperType type) noexcept {
  switch (type) {
    case ShaperType::zv: return 1;
    case ShaperType::zvd: return 2;
    case ShaperType::zvdd: return 3;
    case ShaperType::ei: return 2;
    case ShaperType::mzv: return 1;
  }
  return 1;
}

namespace {

ImpulseTrain normalised(ImpulseTrain t) noexcept {
  const double s = t.sum();
  for (std::size_t i = 0; i < t.count; ++i) t.impulse[i].a /= s;
  return t;
}

}  // namespace

ImpulseTrain design_impulses(ShaperType type, const ModeSpec& mode) noexcept {
  const double root = std::sqrt(1.0 - mode.zeta * mode.zeta);
  const double K = std::exp(-mode.zeta * std::numbers::pi / root);
  const double Td = damped_period_s(mode);
  ImpulseTrain t;
  switch (type) {
    case ShaperType::zv:  // S2: ZV
      t.push(0.0, 1.0);
      t.push(0.5 * Td, K);
      break;
    case ShaperType::zvd:  // S2: ZVD, (1 + K z)^2
      t.push(0.0, 1.0);
      t.push(0.5 * Td, 2.0 * K);
      t.push(Td, K * K);
      break;
    case ShaperType::zvdd:  // S2: ZVDD, (1 + K z)^3
      t.push(0.0, 1.0);
      t.push(0.5 * Td, 3.0 * K);
      t.push(Td, 3.0 * K * K);
      t.push(1.5 * Td, K * K * K);
      break;
    case ShaperType::ei: {  // Singhose's EI, tolerance V, damped by the K weights
      const double V = kEiTolerance;
      t.push(0.0, 0.25 * (1.0 + V));
      t.push(0.5 * Td, 0.5 * (1.0 - V) * K);
      t.push(Td, 0.25 * (1.0 + V) * K * K);
      break;
    }
    case ShaperType::mzv: {  // three impulses 135 deg apart on the damped mode
      const double Km = std::exp(-0.75 * mode.zeta * std::numbers::pi / root);
      const double a1 = 1.0 - 1.0 / std::numbers::sqrt2;
      t.push(0.0, a1);
      t.push(0.375 * Td, (std::numbers::sqrt2 - 1.0) * Km);
      t.push(0.75 * Td, a1 * Km * Km);
      break;
    }
  }
  // ZV/ZVD/ZVDD already sum to 1 up to rounding; normalise all the same way.
  return normalised(t);
}

}  // namespace tnv::fw
