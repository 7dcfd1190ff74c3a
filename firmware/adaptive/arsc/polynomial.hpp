#pragma once
// Fixed-size real polynomials for the gain design, lowest power first:
// p[i] is the coefficient of z^i. No allocation.
#include <array>
#include <complex>
#include <cstddef>

namespace tnv::fw::arsc {

template <std::size_t N>
using Poly = std::array<double, N>;  // degree <= N - 1

template <std::size_t N, std::size_t M>
constexpr Poly<N + M - 1> poly_mul(const Poly<N>& a, const Poly<M>& b) noexcept {
  Poly<N + M - 1> r{};
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t j = 0; j < M; ++j) r[i + j] += a[i] * b[j];
  return r;
}

// a + s b, padded to the longer length R (R >= N, M).
template <std::size_t R, std::size_t N, std::size_t M>
constexpr Poly<R> poly_axpy(const Poly<N>& a, double s, const Poly<M>& b) noexcept {
  static_assert(R >= N && R >= M);
  Poly<R> r{};
  for (std::size_t i = 0; i < N; ++i) r[i] += a[i];
  for (std::size_t i = 0; i < M; ++i) r[i] += s * b[i];
  return r;
}

template <std::size_t R, std::size_t N>
constexpr Poly<R> poly_pad(const Poly<N>& a) noexcept {
  static_assert(R >= N);
  Poly<R> r{};
  for (std::size_t i = 0; i < N; ++i) r[i] = a[i];
  return r;
}

// Monic polynomial with the given roots (complex roots in conjugate pairs),
// returned as [c_0 ... c_{N-1}, 1].
template <std::size_t N>
Poly<N + 1> poly_from_roots(const std::array<std::complex<double>, N>& roots) noexcept {
  std::array<std::complex<double>, N + 1> c{};
  c[0] = 1.0;  // built highest power first: c[0] z^n + c[1] z^{n-1} + ...
  for (std::size_t k = 0; k < N; ++k) {
    for (std::size_t i = k + 1; i > 0; --i) c[i] -= roots[k] * c[i - 1];
  }
  Poly<N + 1> out{};
  for (std::size_t i = 0; i <= N; ++i) out[N - i] = c[i].real();
  return out;
}

}  // namespace tnv::fw::arsc
