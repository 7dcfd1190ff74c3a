#include "firmware/shaper/residual_vibration.hpp"

#include <cmath>
#include <numbers>

namespace tnv::fw {

namespace {

// S2 eq. (1) over any sequence of (t, A) pairs.
template <typename Each>
double residual(double freq_hz, double zeta, double t_last_s, Each each) noexcept {
  const double w = 2.0 * std::numbers::pi * freq_hz;
  const double sigma = zeta * w;
  const double wd = w * std::sqrt(1.0 - zeta * zeta);
  double C = 0.0, S = 0.0;
  each([&](double t_s, double a) {
    // Relative to t_n: e^{-zeta w t_n} e^{zeta w t_i} = e^{zeta w (t_i - t_n)}, no overflow.
    const double g = a * std::exp(sigma * (t_s - t_last_s));
    C += g * std::cos(wd * t_s);
    S += g * std::sin(wd * t_s);
  });
  return std::sqrt(C * C + S * S);
}

// Walks out from the design frequency in small steps until V exceeds the
// tolerance, then bisects the crossing.
template <typename V>
Band band_of(V v, double tolerance) noexcept {
  constexpr double kStep = 0.005;
  constexpr double kLowest = 0.05, kHighest = 3.0;
  Band b;
  if (!(v(1.0) <= tolerance)) return {1.0, 1.0};
  for (int side = -1; side <= 1; side += 2) {
    double inside = 1.0, outside = 1.0;
    bool found = false;
    for (double r = 1.0 + side * kStep; r > kLowest && r < kHighest; r += side * kStep) {
      if (v(r) > tolerance) {
        outside = r;
        found = true;
        break;
      }
      inside = r;
    }
    double edge = inside;
    if (found) {
      for (int i = 0; i < 40; ++i) {
        const double mid = 0.5 * (inside + outside);
        (v(mid) <= tolerance ? inside : outside) = mid;
      }
      edge = inside;
    }
    (side < 0 ? b.low_ratio : b.high_ratio) = edge;
  }
  return b;
}

}  // namespace

double residual_vibration(const ImpulseTrain& train, double freq_hz, double zeta) noexcept {
  return residual(freq_hz, zeta, train.duration_s(), [&](auto&& f) {
    for (std::size_t i = 0; i < train.count; ++i) f(train.impulse[i].t_s, train.impulse[i].a);
  });
}

double residual_vibration(const TapSet& taps, double period_s, double freq_hz, double zeta) noexcept {
  return residual(freq_hz, zeta, static_cast<double>(taps.span()) * period_s, [&](auto&& f) {
    for (std::size_t i = 0; i < taps.count; ++i) f(static_cast<double>(taps.tap[i].k) * period_s, taps.tap[i].a);
  });
}

Band insensitivity_band(const ImpulseTrain& train, double design_hz, double zeta, double tolerance) noexcept {
  return band_of([&](double r) { return residual_vibration(train, r * design_hz, zeta); }, tolerance);
}

Band insensitivity_band(const TapSet& taps, double period_s, double design_hz, double zeta, double tolerance) noexcept {
  return band_of([&](double r) { return residual_vibration(taps, period_s, r * design_hz, zeta); }, tolerance);
}

}  // namespace tnv::fw
