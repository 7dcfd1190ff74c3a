#pragma once
// Cutting force of a 2-flute end mill on the commanded circle, as a table
// speed disturbance (reference plant "Cutting"):
//   d_cut = (v_feed / F) (900/S)^exponent [c_m + c_a sin(2 pi N S/60 t + phi0)] u_hat
// v_feed and the feed direction come from the commanded circle; u_hat
// opposes the feed, rotated 45 deg toward the outward normal:
//   u_hat = (-t_hat + n_hat) / sqrt 2,  t_hat = (-sin th, cos th),  n_hat = (cos th, sin th).
// t is time since the machine was constructed. The tooth phase is an exact
// sin/cos at the start of each fill, turned by precomputed exact rotations.
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "emulator/circle_path_stepper.hpp"
#include "emulator/phasor.hpp"
#include "emulator/scenario.hpp"
#include "hal/axis.hpp"

namespace tnv::emu {

struct CuttingVector {
  double x_mm_s = 0.0;
  double y_mm_s = 0.0;
  double component(hal::Axis axis) const noexcept { return axis == hal::Axis::x ? x_mm_s : y_mm_s; }
  double magnitude_mm_s() const noexcept { return std::hypot(x_mm_s, y_mm_s); }
};

class CuttingDisturbance {
 public:
  // Longest fill (one tick at the default divider).
  static constexpr std::size_t kMaxFill = 100;

  CuttingDisturbance(const CuttingParams& cutting, const CircleParams& circle) noexcept;

  bool enabled() const noexcept { return enabled_; }
  double frequency_hz() const noexcept { return frequency_hz_; }  // N S / 60
  void servo_on_at(double time_s) noexcept { path_.servo_on_at(time_s); }
  const CirclePathStepper& path() const noexcept { return path_; }

  // d_cut at sub-step boundary `substep`, exact (uses sin/cos).
  CuttingVector at_substep(std::uint64_t substep) const noexcept {
    CuttingVector d;
    fill(substep, 1, &d.x_mm_s, &d.y_mm_s);
    return d;
  }
  // d_cut for `count` (<= kMaxFill) consecutive sub-steps, exact to rounding.
  void fill(std::uint64_t first_substep, std::size_t count, double* x_mm_s, double* y_mm_s) const noexcept;

 private:
  Phasor tooth_phase(std::uint64_t substep) const noexcept;  // 2 pi N S/60 t + phi0

  bool enabled_;
  double frequency_hz_;
  double phase_rad_;
  double mean_mm_s_;
  double amplitude_mm_s_;
  double gain_per_feed_;  // (900/S)^exponent / F
  std::array<Phasor, kMaxFill> tooth_powers_;  // multiples of 2 pi N S/60 h
  CirclePathStepper path_;
};

inline void CuttingDisturbance::fill(std::uint64_t first_substep, std::size_t count, double* x_mm_s,
                                     double* y_mm_s) const noexcept {
  if (!enabled_) {
    for (std::size_t i = 0; i < count; ++i) x_mm_s[i] = y_mm_s[i] = 0.0;
    return;
  }
  assert(count <= kMaxFill);
  double speed_mm_s[kMaxFill], cos_angle[kMaxFill], sin_angle[kMaxFill];
  path_.fill(first_substep, count, speed_mm_s, cos_angle, sin_angle);
  const Phasor tooth0 = tooth_phase(first_substep);
  constexpr double kInvSqrt2 = 0.70710678118654752440;
  for (std::size_t i = 0; i < count; ++i) {
    const double tooth_sin = tooth0.rotated(tooth_powers_[i]).sin_a;
    // Zero feed gives zero force: no chip.
    const double level_mm_s = gain_per_feed_ * speed_mm_s[i] * (mean_mm_s_ + amplitude_mm_s_ * tooth_sin);
    x_mm_s[i] = level_mm_s * kInvSqrt2 * (sin_angle[i] + cos_angle[i]);
    y_mm_s[i] = level_mm_s * kInvSqrt2 * (sin_angle[i] - cos_angle[i]);
  }
}

}  // namespace tnv::emu
