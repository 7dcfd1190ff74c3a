#pragma once
// The one pole computation: the eigenvalues of a small fixed-size state
// matrix (a closed loop, an observer's error dynamics, a companion matrix).
// Configuration time only (Eigen's real Schur form, no eigenvectors); a
// failed decomposition gives poles at infinity so that every stability
// check on them fails.
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <array>
#include <complex>
#include <cstddef>
#include <limits>

namespace tnv::fw {

template <int N>
using MatrixPoles = std::array<std::complex<double>, static_cast<std::size_t>(N)>;

template <int N>
MatrixPoles<N> matrix_poles(const Eigen::Matrix<double, N, N>& a) noexcept {
  const Eigen::EigenSolver<Eigen::Matrix<double, N, N>> solver(a, false);
  MatrixPoles<N> poles{};
  if (solver.info() != Eigen::Success) {
    poles.fill({std::numeric_limits<double>::infinity(), 0.0});
    return poles;
  }
  for (int i = 0; i < N; ++i) poles[static_cast<std::size_t>(i)] = solver.eigenvalues()(i);
  return poles;
}

}  // namespace tnv::fw
