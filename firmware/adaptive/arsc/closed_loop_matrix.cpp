#include "firmware/adaptive/arsc/closed_loop_matrix.hpp"

namespace tnv::fw::arsc {

Matrix7 closed_loop_matrix(const Arv2Model& m, const ArscGains& g) noexcept {
  const Eigen::Matrix2d& p1 = m.phi1;
  const Eigen::Matrix2d& p2 = m.phi2;
  const double t1 = m.theta0(0), t2 = m.theta0(1);
  Matrix7 a = Matrix7::Zero();
  // S3 eqs. (2), (11): x(t+1) = Phi x(t) + Gamma u(t), u = k eta + [g31 g32] y + [g41 g42] eps
  const double u_row[7] = {0.0, 0.0, g.gamma31, g.gamma32, g.k, g.gamma41, g.gamma42};
  for (int c = 0; c < 7; ++c) {
    a(0, c) = t1 * u_row[c];
    a(1, c) = t2 * u_row[c];
  }
  a(0, 2) -= p2(0, 0);
  a(0, 3) -= p2(0, 1);
  a(1, 2) -= p2(1, 0);
  a(1, 3) -= p2(1, 1);
  a(2, 0) = 1.0;
  a(2, 2) = -p1(0, 0);
  a(2, 3) = -p1(0, 1);
  a(3, 1) = 1.0;
  a(3, 2) = -p1(1, 0);
  a(3, 3) = -p1(1, 1);
  // S3 eq. (7): eta(t+1) = eta(t) + f(t) - f*(t)
  a(4, 2) = 1.0;
  a(4, 4) = 1.0;
  // S3 eq. (10): stabilising compensator
  a(5, 2) = g.gamma11;
  a(5, 3) = g.gamma12;
  a(5, 4) = g.gamma21;
  a(5, 5) = g.gamma01;
  a(5, 6) = g.gamma02;
  a(6, 3) = g.gamma13;
  a(6, 4) = g.gamma22;
  a(6, 6) = g.gamma03;
  return a;
}

}  // namespace tnv::fw::arsc
