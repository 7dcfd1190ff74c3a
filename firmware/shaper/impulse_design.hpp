#pragma once
// Closed-form impulse sequences for one mode (natural frequency f, damping
// ratio zeta). With K = exp(-zeta pi / sqrt(1 - zeta^2)) and the damped
// period T_d = 1 / (f sqrt(1 - zeta^2)):
//   ZV   (S2):  [1, K] / (1 + K)                         at 0, T_d/2
//   ZVD  (S2):  [1, 2K, K^2] / (1 + K)^2                 at 0, T_d/2, T_d
//   ZVDD (S2):  [1, 3K, 3K^2, K^3] / (1 + K)^3           at 0, T_d/2, T_d, 3T_d/2
//   EI, tolerance V = 5 % (Singhose): [(1+V)/4, (1-V)/2 K, (1+V)/4 K^2] / sum
//                                                        at 0, T_d/2, T_d
//   MZV: with K' = exp(-0.75 zeta pi / sqrt(1 - zeta^2)):
//        [1 - 1/sqrt2, (sqrt2 - 1) K', (1 - 1/sqrt2) K'^2] / sum
//                                                        at 0, 3T_d/8, 3T_d/4
// ZV, ZVD, ZVDD and MZV put V = 0 exactly on the design mode; EI leaves
// about its tolerance there (exactly V at zeta = 0) and trades it for
// the widest band.
#include "firmware/control/param_check.hpp"
#include "firmware/shaper/impulse_train.hpp"
#include "firmware/shaper/shaper_type.hpp"

namespace tnv::fw {

struct ModeSpec {
  double freq_hz = 30.0;
  double zeta = 0.0;
};

// Design range: what the ring buffer is sized for and the grid solver is
// proven on (tests sweep it).
inline constexpr double kShaperMinFreqHz = 5.0;
inline constexpr double kShaperMaxFreqHz = 200.0;
inline constexpr double kShaperMaxZeta = 0.3;
inline constexpr double kEiTolerance = 0.05;

// field "freq_hz" / "zeta"; ok when inside the design range and finite.
ParamCheck validate(const ModeSpec& mode) noexcept;

// Requires validate(mode).ok.
ImpulseTrain design_impulses(ShaperType type, const ModeSpec& mode) noexcept;

// Zero-vibration conditions the shaper meets at the design pole: the
// residual and its first (multiplicity - 1) derivatives in frequency.
// EI has no zero there; it is matched on value and slope (see grid_taps).
int design_multiplicity(ShaperType type) noexcept;

// Damped period T_d = 1 / (f sqrt(1 - zeta^2)).
double damped_period_s(const ModeSpec& mode) noexcept;

}  // namespace tnv::fw
