#pragma once
// The global closed-loop matrix Phi^(K) of S3 eq. (12), Fig. 2, for
// X = [x1 x2 x3 x4 eta eps1 eps2]^T, and the characteristic-polynomial
// coefficients of any small square matrix. Used to prove the gain design
// (tests, `tnv-hil arsc design`); not in the per-sample path.
//
// Fig. 2 with its signs restored from eqs. (2), (7), (10), (11): the plant
// rows are Phi + Gamma [0 0 gamma31 gamma32 k gamma41 gamma42], i.e. the
// control computed from X(t) enters x1, x2 at t+1. That is exact for the
// ARV(2) model (1) when the control computed at sample t is applied from
// t+1 (one-sample computation delay): the timing this module implements.
#include <Eigen/Core>
#include <array>
#include <cstddef>

#include "firmware/adaptive/arsc/arsc_gains.hpp"
#include "firmware/adaptive/arsc/arv2_model.hpp"

namespace tnv::fw::arsc {

using Matrix7 = Eigen::Matrix<double, 7, 7>;

Matrix7 closed_loop_matrix(const Arv2Model& model, const ArscGains& gains) noexcept;

// [d1, ..., dN] of det(mu I - M) = mu^N + d1 mu^{N-1} + ... + dN
// (Faddeev-LeVerrier; fine for the small, well-scaled matrices here).
template <int N>
std::array<double, static_cast<std::size_t>(N)> characteristic_coefficients(
    const Eigen::Matrix<double, N, N>& m) noexcept {
  using Mat = Eigen::Matrix<double, N, N>;
  std::array<double, static_cast<std::size_t>(N)> d{};
  Mat b = Mat::Identity();
  for (int k = 1; k <= N; ++k) {
    const Mat mb = m * b;
    const double c = -mb.trace() / static_cast<double>(k);
    d[static_cast<std::size_t>(k - 1)] = c;
    b = mb + c * Mat::Identity();
  }
  return d;
}

}  // namespace tnv::fw::arsc
