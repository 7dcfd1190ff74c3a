#pragma once
// Cutting force of a 2-flute end mill as a table-speed disturbance that
// follows the table's own motion (reference plant "Cutting", generalised
// from the S1 circle to any path; docs/scenarios.md):
//   d_cut = (v_feed / F) (900/S)^exponent [c_m + c_a sin(2 pi N S/60 t + phi0)] u_hat
// v = (v_x, v_y) is the table's actual velocity at the start of each 10 us
// sub-step (held over it, as the plant holds friction), v_feed = |v|, and
// u_hat opposes the direction of travel t_hat = v / |v|, rotated 45 deg
// toward its right-hand side r_hat = (t_y, -t_x), where the outward normal
// of a counter-clockwise circle lies (so on the S1 circle this is the
// reference plant's model):
//   u_hat = (-t_hat + r_hat) / sqrt 2,   v_feed u_hat = (-v + (v_y, -v_x)) / sqrt 2.
// Linear in v: zero at rest, no direction to define there, no sqrt. F is
// the programmed feed, the feed at which the mean load is c_m. t is time
// since the machine was constructed; the tooth phase is an exact sin/cos at
// the start of each fill, turned by precomputed exact rotations.
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "emulator/phasor.hpp"
#include "emulator/scenario.hpp"
#include "hal/axis.hpp"

namespace tnv::emu {

// The cut's disturbance, in the XY plane (kPlaneFirst, kPlaneSecond); 0 on any other axis.
struct CuttingVector {
  double x_mm_s = 0.0;
  double y_mm_s = 0.0;
  double component(hal::Axis axis) const noexcept {
    return axis == hal::kPlaneFirst ? x_mm_s : axis == hal::kPlaneSecond ? y_mm_s : 0.0;
  }
  double magnitude_mm_s() const noexcept { return std::hypot(x_mm_s, y_mm_s); }
};

class CuttingDisturbance {
 public:
  // Longest fill (one tick at the default divider).
  static constexpr std::size_t kMaxFill = 100;

  CuttingDisturbance(const CuttingParams& cutting, double programmed_feed_mm_s) noexcept;

  bool enabled() const noexcept { return enabled_; }
  double frequency_hz() const noexcept { return frequency_hz_; }  // N S / 60

  // (900/S)^exponent / F [c_m + c_a sin(2 pi N S/60 t + phi0)]: mm/s of
  // d_cut per mm/s of table speed, for `count` (<= kMaxFill) consecutive
  // sub-steps from `first_substep`, exact to rounding. Zero when disabled.
  void fill_load_per_speed(std::uint64_t first_substep, std::size_t count, double* load_per_speed) const noexcept;

  // d_cut for a load per speed (above) and the table's velocity.
  static CuttingVector force(double load_per_speed, double speed_x_mm_s, double speed_y_mm_s) noexcept {
    constexpr double kInvSqrt2 = 0.70710678118654752440;
    const double k = load_per_speed * kInvSqrt2;
    return {k * (speed_y_mm_s - speed_x_mm_s), -k * (speed_x_mm_s + speed_y_mm_s)};
  }
  // d_cut at sub-step `substep` with the table moving at (v_x, v_y), exact (uses sin/cos).
  CuttingVector at_substep(std::uint64_t substep, double speed_x_mm_s, double speed_y_mm_s) const noexcept {
    double load_per_speed = 0.0;
    fill_load_per_speed(substep, 1, &load_per_speed);
    return force(load_per_speed, speed_x_mm_s, speed_y_mm_s);
  }

 private:
  Phasor tooth_phase(std::uint64_t substep) const noexcept;  // 2 pi N S/60 t + phi0

  bool enabled_;
  double frequency_hz_;
  double phase_rad_;
  double mean_per_speed_;       // (900/S)^exponent c_m / F
  double amplitude_per_speed_;  // (900/S)^exponent c_a / F
  std::array<Phasor, kMaxFill> tooth_powers_;  // multiples of 2 pi N S/60 h
};

inline void CuttingDisturbance::fill_load_per_speed(std::uint64_t first_substep, std::size_t count,
                                                    double* load_per_speed) const noexcept {
  if (!enabled_) {
    for (std::size_t i = 0; i < count; ++i) load_per_speed[i] = 0.0;
    return;
  }
  assert(count <= kMaxFill);
  const Phasor tooth0 = tooth_phase(first_substep);
  for (std::size_t i = 0; i < count; ++i) {
    load_per_speed[i] = mean_per_speed_ + amplitude_per_speed_ * tooth0.rotated(tooth_powers_[i]).sin_a;
  }
}

}  // namespace tnv::emu
