#pragma once
// Shared helpers for the ARSC tests: random ARV(2) models with a stable
// open loop (Jury), seeded, and the S3 process written as an ARV(2) model.
#include <Eigen/LU>
#include <random>

#include "firmware/adaptive/arsc/arv2_model.hpp"
#include "firmware/adaptive/arsc/jury_stability.hpp"

namespace tnv::fw::arsc::test {

inline Arv2Model random_stable_model(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  for (;;) {
    Arv2Model m;
    m.phi1 << u(rng), u(rng), u(rng), u(rng);
    m.phi2 << 0.5 * u(rng), 0.5 * u(rng), 0.5 * u(rng), 0.5 * u(rng);
    m.theta0 << u(rng), 0.2 + std::fabs(u(rng));
    if (jury_quartic(open_loop_quartic(m)).stable && std::fabs(m.phi1.determinant()) > 0.02) return m;
  }
}

// S3 eqs. (27)-(28) at depth delta with the one-sample computation delay:
// Phi1 = [a21, -b21 delta; b11, a11], Phi2 = 0, theta0 = [0; b11].
inline Arv2Model s3_process_model(double delta_mm) {
  const double a11 = -0.5488, b11 = 0.4512, a21 = -0.4724, b21 = 0.7915;
  Arv2Model m;
  m.phi1 << a21, -b21 * delta_mm, b11, a11;
  m.theta0 << 0.0, b11;
  return m;
}

}  // namespace tnv::fw::arsc::test
