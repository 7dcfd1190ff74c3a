#pragma once
// Putting a continuous shaper on the 1 ms control grid.
//
// Rounding moves each impulse to the nearest sample (phase error up to
// w T/2: ~15 % residual near 100 Hz). Splitting shares each impulse
// linearly between its two neighbouring samples (the zero moves by the
// interpolation error: 2-3 % near 100 Hz, ~10 % at 200 Hz).
//
// exact_grid_taps: re-solve the amplitudes on a few samples around every
// impulse so that the grid shaper's zeros land exactly on the mode. With
// the grid transfer function H_g(s) = sum a_k e^{-s k T} and the
// continuous one H_c(s) = sum A_i e^{-s t_i}, at the design pole
// p = -zeta w + i w_d the taps satisfy
//   sum a_k = 1                                   (unit static gain)
//   H_g^(j)(p) = H_c^(j)(p),  j = 0 .. J-1        (real and imaginary parts)
// For ZV/ZVD/ZVDD/MZV, H_c and its first m-1 derivatives vanish at p
// (m = design_multiplicity), so with J >= m the grid shaper has the same
// m-fold zero exactly on the mode: V = 0 to rounding. EI (no zero there,
// m = 2) is matched the same way on value and derivatives, so its
// residual at the mode is the continuous one. Among all solutions the taps closest (least squares) to
// the split taps are taken: a = a0 + C^T (C C^T)^-1 (d - C a0).
// The candidate samples are k-1 .. k+2 around each impulse (k = floor(t/T)).
// Taps are kept non-negative (a shaped move never backs up) by a small
// active set: the most negative tap is dropped and the system re-solved.
// First J = m + 1 is tried (one more derivative keeps the slope of V(w) at
// the mode, hence the insensitivity band); if that has no non-negative
// solution, J = m; if neither has, the J = m solution with its negative
// taps (not seen for 5-200 Hz, zeta <= 0.3 at 1 kHz).
#include "firmware/shaper/impulse_design.hpp"
#include "firmware/shaper/impulse_train.hpp"
#include "firmware/shaper/tap_set.hpp"

namespace tnv::fw {

TapSet round_to_grid(const ImpulseTrain& train, double period_s) noexcept;
TapSet split_to_grid(const ImpulseTrain& train, double period_s) noexcept;

// Requires validate(mode).ok and period_s > 0. Returns the split taps
// (never a half-solved set) in the unexpected case the system is singular.
TapSet exact_grid_taps(ShaperType type, const ModeSpec& mode, double period_s) noexcept;

}  // namespace tnv::fw
