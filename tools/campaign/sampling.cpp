#include "tools/campaign/sampling.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace tnv::campaign {

std::uint64_t splitmix64(std::uint64_t& state) noexcept {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

std::uint64_t mix64(std::uint64_t value) noexcept { return splitmix64(value); }

double unit_open(std::uint64_t& state) noexcept {
  // 53 random bits, offset by half a step: (k + 0.5) / 2^53 is in (0, 1).
  const std::uint64_t k = splitmix64(state) >> 11;
  return (static_cast<double>(k) + 0.5) * 0x1.0p-53;
}

double inverse_normal_cdf(double p) noexcept {
  static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                                 1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                                 6.680131188771972e+01,  -1.328068155288572e+01};
  static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                                 -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                                 3.754408661907416e+00};
  constexpr double p_low = 0.02425;
  double x;
  if (p < p_low) {
    const double q = std::sqrt(-2.0 * std::log(p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  } else if (p <= 1.0 - p_low) {
    const double q = p - 0.5;
    const double r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
  } else {
    const double q = std::sqrt(-2.0 * std::log1p(-p));
    x = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  }
  // One Halley step on Phi(x) - p, Phi from erfc.
  const double e = 0.5 * std::erfc(-x / std::sqrt(2.0)) - p;
  const double u = e * std::sqrt(2.0 * 3.14159265358979323846) * std::exp(x * x / 2.0);
  return x - u / (1.0 + x * u / 2.0);
}

std::vector<double> unit_samples(std::size_t runs, std::size_t dims, std::uint64_t seed, Sampling sampling) {
  std::vector<double> out(runs * dims);
  std::uint64_t state = mix64(seed);
  if (sampling == Sampling::random) {
    for (double& v : out) v = unit_open(state);
    return out;
  }
  std::vector<std::size_t> strata(runs);
  for (std::size_t d = 0; d < dims; ++d) {
    std::iota(strata.begin(), strata.end(), std::size_t{0});
    for (std::size_t i = runs; i > 1; --i) {  // Fisher-Yates with our generator
      const std::size_t j = static_cast<std::size_t>(splitmix64(state) % i);
      std::swap(strata[i - 1], strata[j]);
    }
    for (std::size_t r = 0; r < runs; ++r) {
      const double v = (static_cast<double>(strata[r]) + unit_open(state)) / static_cast<double>(runs);
      out[r * dims + d] = std::min(v, std::nextafter(1.0, 0.0));  // rounding must not reach 1
    }
  }
  return out;
}

}  // namespace tnv::campaign
