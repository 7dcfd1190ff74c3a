#include "firmware/adaptive/arsc/pole_sets.hpp"

#include <cmath>
#include <numbers>

#include "firmware/adaptive/arsc/polynomial.hpp"

namespace tnv::fw::arsc {

namespace {

std::complex<double> at_deg(double radius, double angle_deg) noexcept {
  return std::polar(radius, angle_deg * std::numbers::pi / 180.0);
}

Poles7 real_plus_triple_pair(double real_pole, double radius, double angle_deg) noexcept {
  const std::complex<double> p = at_deg(radius, angle_deg);
  return {real_pole, p, std::conj(p), p, std::conj(p), p, std::conj(p)};
}

// [c_{n-1}, ..., c_0] of the monic polynomial -> d* order (highest first).
template <std::size_t N>
std::array<double, N> to_d_star(const Poly<N + 1>& p) noexcept {
  std::array<double, N> d{};
  for (std::size_t i = 0; i < N; ++i) d[i] = p[N - 1 - i];
  return d;
}

}  // namespace

std::optional<PoleSet> parse_pole_set(std::string_view name) noexcept {
  if (name == "case1") return PoleSet::case1;
  if (name == "case2") return PoleSet::case2;
  if (name == "case3") return PoleSet::case3;
  if (name == "case4") return PoleSet::case4;
  return std::nullopt;
}

Poles7 paper_poles(PoleSet set) noexcept {
  switch (set) {
    case PoleSet::case1: return {0.21, 0.21, 0.21, 0.21, 0.21, 0.21, 0.21};
    case PoleSet::case2: return {0.3, 0.3, 0.3, 0.3, 0.3, 0.3, 0.3};
    case PoleSet::case3: return real_plus_triple_pair(0.19, 0.2, 68.8);
    case PoleSet::case4: return real_plus_triple_pair(0.25, 0.3, 51.8);
  }
  return {};
}

Poles7 poles_at_period(const Poles7& poles, double period_s) noexcept {
  const double ratio = period_s / kPaperSamplePeriod_s;
  Poles7 out{};
  for (std::size_t i = 0; i < poles.size(); ++i) out[i] = std::pow(poles[i], ratio);
  return out;
}

Poles6 six_of_seven(const Poles7& poles) noexcept {
  Poles6 out{};
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = poles[i + 1];
  return out;
}

std::array<double, 7> desired_coefficients(const Poles7& poles) noexcept {
  return to_d_star<7>(poly_from_roots(poles));
}

std::array<double, 6> desired_coefficients(const Poles6& poles) noexcept {
  return to_d_star<6>(poly_from_roots(poles));
}

}  // namespace tnv::fw::arsc
