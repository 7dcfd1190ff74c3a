#pragma once
// Residual vibration of an impulse sequence on a mode (S2 eq. (1)):
//   V(w, zeta) = e^{-zeta w t_n} sqrt(C^2 + S^2),
//   C = sum A_i e^{zeta w t_i} cos(w_d t_i),  S = sum A_i e^{zeta w t_i} sin(w_d t_i),
//   w_d = w sqrt(1 - zeta^2), t_n = time of the last impulse.
// The ratio of the shaped to the unshaped vibration amplitude, each taken
// at the end of its own input. Taps are impulses at t = k * period.
#include "firmware/shaper/impulse_train.hpp"
#include "firmware/shaper/tap_set.hpp"

namespace tnv::fw {

// Fraction (0.05 = 5 %), not percent.
double residual_vibration(const ImpulseTrain& train, double freq_hz, double zeta) noexcept;
double residual_vibration(const TapSet& taps, double period_s, double freq_hz, double zeta) noexcept;

// The insensitivity band: the interval of actual frequencies around the
// design frequency over which V stays at or below `tolerance` (contiguous,
// containing the design frequency), as a fraction of the design frequency.
// 0 when V at the design frequency is already above the tolerance.
struct Band {
  double low_ratio = 1.0;   // f_low / f_design
  double high_ratio = 1.0;  // f_high / f_design
  double width() const noexcept { return high_ratio - low_ratio; }
};
Band insensitivity_band(const ImpulseTrain& train, double design_hz, double zeta, double tolerance = 0.05) noexcept;
Band insensitivity_band(const TapSet& taps, double period_s, double design_hz, double zeta,
                        double tolerance = 0.05) noexcept;

}  // namespace tnv::fw
