#pragma once
// Gain design of the outer ARSC (the force loop over the axis controller)
// at its own rate, in delta-operator form so that the same design works
// from the 1 ms tick to the paper's 0.15 s (issue 8 item 5).
//
// Loop (normalised units, FeedForceModel sampled at period T):
//   x(t+1)  = Phi x(t) + Gamma0 u(t) + Gamma1 u(t-1),  x = [f, v]
//   eta(t+1) = eta(t) + T (f(t) - f*(t))            S3 eq. (7), integral in seconds
//   u(t)    = k eta(t) + g31 f(t) + g32 v(t) + g33 u(t-1)   S3 eq. (11), with the
//             input in flight u(t-1) in place of the stabilising compensator (10)
// State z = [f, v, u(t-1), eta]: 4th-order closed loop. (10) is the paper's
// output-feedback device for an ARV(2) model with unmeasured states; here
// every state is measured (force, feed) or known (the command in flight).
//
// Delta operator: delta = (q - 1) / T. The closed-loop matrix A_d + B_d K
// with A_d = (A - I) / T, B_d = B / T tends to the continuous-time loop as
// T -> 0, so poles near z = 1 (a fast rate) stay well separated in delta
// and the gain equations stay well conditioned, unlike the z-domain
// coefficients of the paper's clustered pole sets.
//
// Poles (the pole-set idea of S3 Fig. 7, made rate-independent): the two
// force-loop poles are given in continuous time (rad/s) and mapped with
// z = exp(s T); the drive keeps its own pole (exp(-T / tau_v)) and the
// input in flight is dead-beat (z = 0): the force loop does not fight the
// axis controller. The gains come from the characteristic-polynomial
// identity det(lambda I - A_d - B_d K) = prod(lambda - delta_i), linear in K,
// solved with column scaling by a rank-revealing decomposition (at slow
// rates the drive and the input in flight are the same mode: the
// minimum-norm gains place it where it already is).
#include <array>
#include <complex>

#include "firmware/adaptive/arsc/feed_force_model.hpp"
#include "firmware/adaptive/arsc/gain_guard.hpp"
#include "firmware/control/param_check.hpp"

namespace tnv::fw::arsc {

struct OuterGains {
  double k = 0.0;        // on eta (per normalised force-second)
  double gamma31 = 0.0;  // on f
  double gamma32 = 0.0;  // on v
  double gamma33 = 0.0;  // on u(t-1), the command in flight
};

// The force-loop pole pair in continuous time: both real (im = 0) or a
// conjugate pair (force_s[1] = conj(force_s[0])). Re < 0.
struct OuterPoles {
  std::array<std::complex<double>, 2> force_s{std::complex<double>{-10.0, 0.0}, std::complex<double>{-10.0, 0.0}};
};

struct OuterDesignLimits {
  double max_gain = 1.0e3;    // any |gain| above: refuse (keep the last good gains)
  double rank_tolerance = 1e-9;  // relative, of the column-scaled gain equations
};

ParamCheck validate(const OuterPoles& poles) noexcept;
ParamCheck validate(const OuterDesignLimits& limits) noexcept;

struct OuterDesign {
  OuterGains gains{};
  GuardReason reason = GuardReason::model_not_finite;
  double rcond = 0.0;  // smallest / largest |R diagonal| of the scaled equations
};

OuterDesign solve_outer_gains(const SampledFeedForce& plant, double period_s, const OuterPoles& poles,
                              const OuterDesignLimits& limits) noexcept;

// The closed-loop matrix in z (4 x 4, state [f, v, u(t-1), eta]) for given
// gains, to check a design.
Eigen::Matrix4d outer_closed_loop(const SampledFeedForce& plant, double period_s, const OuterGains& gains) noexcept;

// The four z-plane poles the design asks for.
std::array<std::complex<double>, 4> outer_target_poles(const SampledFeedForce& plant, double period_s,
                                                       const OuterPoles& poles) noexcept;

}  // namespace tnv::fw::arsc
