#pragma once
// Dense Gaussian elimination with partial pivoting for the tiny systems of
// the grid-tap solver (at most 9 x 9). Fixed storage, no allocation.
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>

namespace tnv::fw {

template <typename T, std::size_t N>
using SmallMatrix = std::array<std::array<T, N>, N>;

// Solves the leading n x n block of m x = b in place (x returned in b).
// False when the matrix is singular to working precision.
template <typename T, std::size_t N>
bool solve_in_place(SmallMatrix<T, N>& m, std::array<T, N>& b, std::size_t n) noexcept {
  T scale = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) scale = std::fmax(scale, std::fabs(m[i][j]));
  if (!(scale > 0)) return false;
  for (std::size_t col = 0; col < n; ++col) {
    std::size_t pivot = col;
    for (std::size_t r = col + 1; r < n; ++r)
      if (std::fabs(m[r][col]) > std::fabs(m[pivot][col])) pivot = r;
    if (!(std::fabs(m[pivot][col]) > T(1e-30) * scale)) return false;
    std::swap(m[pivot], m[col]);
    std::swap(b[pivot], b[col]);
    for (std::size_t r = col + 1; r < n; ++r) {
      const T f = m[r][col] / m[col][col];
      for (std::size_t c = col; c < n; ++c) m[r][c] -= f * m[col][c];
      b[r] -= f * b[col];
    }
  }
  for (std::size_t i = n; i-- > 0;) {
    T acc = b[i];
    for (std::size_t c = i + 1; c < n; ++c) acc -= m[i][c] * b[c];
    b[i] = acc / m[i][i];
  }
  return true;
}

}  // namespace tnv::fw
