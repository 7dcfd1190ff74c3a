#pragma once
// The robust servo controller of S3 section 2.3: servo compensator (7),
// stabilising compensator (10) and control law (11). Shared by both ARSC
// variants. Normalised units (force and feed divided by their references).
#include "firmware/adaptive/arsc/arsc_gains.hpp"

namespace tnv::fw::arsc {

struct ServoState {
  double eta = 0.0;   // servo compensator (integral of the force error)
  double eps1 = 0.0;  // stabilising compensator
  double eps2 = 0.0;
};

// S3 eq. (11): u(t) = k eta(t) + [g31 g32] y(t) + [g41 g42] eps(t)
inline double servo_control(const ArscGains& g, const ServoState& s, double force, double feed) noexcept {
  return g.k * s.eta + g.gamma31 * force + g.gamma32 * feed + g.gamma41 * s.eps1 + g.gamma42 * s.eps2;
}

// S3 eqs. (7), (10): the compensator states at t+1.
inline ServoState servo_advance(const ArscGains& g, const ServoState& s, double force, double feed,
                                double force_ref) noexcept {
  ServoState n;
  n.eta = s.eta + (force - force_ref);                                                         // (7)
  n.eps1 = g.gamma01 * s.eps1 + g.gamma02 * s.eps2 + g.gamma11 * force + g.gamma12 * feed + g.gamma21 * s.eta;  // (10)
  n.eps2 = g.gamma03 * s.eps2 + g.gamma13 * feed + g.gamma22 * s.eta;                          // (10)
  return n;
}

}  // namespace tnv::fw::arsc
