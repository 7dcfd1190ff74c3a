#pragma once
// The ARV(2) process model of S3 eq. (1), y = [f, v]^T (normalised peak
// force and feed), single input u:
//   y(t) + Phi1 y(t-1) + Phi2 y(t-2) = theta0 u(t-1)
#include <Eigen/Core>
#include <array>

namespace tnv::fw::arsc {

struct Arv2Model {
  Eigen::Matrix2d phi1 = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d phi2 = Eigen::Matrix2d::Zero();
  Eigen::Vector2d theta0 = Eigen::Vector2d::Zero();
};

// The starting estimates of the paper's simulation, S3 eq. (29).
inline Arv2Model paper_initial_model() noexcept {
  Arv2Model m;
  m.phi1 << -0.12, -0.16, 0.07, -0.28;
  m.phi2 << -0.03, -0.17, 0.1, -0.06;
  m.theta0 << 0.0, 0.5;
  return m;
}

inline bool is_finite(const Arv2Model& m) noexcept {
  return m.phi1.allFinite() && m.phi2.allFinite() && m.theta0.allFinite();
}

// Coefficients [d1, d2, d3, d4] of det(z^2 I + Phi1 z + Phi2)
// = z^4 + d1 z^3 + d2 z^2 + d3 z + d4, S3 eq. (30).
inline std::array<double, 4> open_loop_quartic(const Arv2Model& m) noexcept {
  const Eigen::Matrix2d& a = m.phi1;
  const Eigen::Matrix2d& b = m.phi2;
  return {a(0, 0) + a(1, 1),                                                        // S3 eq. (30): d1
          b(0, 0) + b(1, 1) + a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0),                // d2
          b(0, 0) * a(1, 1) + b(1, 1) * a(0, 0) - b(0, 1) * a(1, 0) - b(1, 0) * a(0, 1),  // d3
          b(0, 0) * b(1, 1) - b(0, 1) * b(1, 0)};                                   // d4
}

}  // namespace tnv::fw::arsc
