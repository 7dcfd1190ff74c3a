#pragma once
// Small dense solve for the gain equations, fixed size, no allocation.
#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>

namespace tnv::fw::arsc {

// Solves a x = b with the columns of a scaled to unit max-norm (the gains
// have different sizes); rcond of the scaled matrix. false if singular.
template <int N>
inline bool solve_scaled(const Eigen::Matrix<double, N, N>& a, const Eigen::Matrix<double, N, 1>& b, double min_rcond,
                  Eigen::Matrix<double, N, 1>& x, double& rcond) noexcept {
  Eigen::Matrix<double, N, 1> scale;
  for (int j = 0; j < N; ++j) {
    scale(j) = a.col(j).cwiseAbs().maxCoeff();
    if (!(scale(j) > 0.0) || !std::isfinite(scale(j))) {
      rcond = 0.0;
      return false;
    }
  }
  const Eigen::Matrix<double, N, N> scaled = a * scale.cwiseInverse().asDiagonal();
  const Eigen::PartialPivLU<Eigen::Matrix<double, N, N>> lu(scaled);
  rcond = lu.rcond();
  if (!(rcond >= min_rcond)) return false;
  x = lu.solve(b).cwiseQuotient(scale);
  return true;
}

}  // namespace tnv::fw::arsc
