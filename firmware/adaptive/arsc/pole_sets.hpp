#pragma once
// The four desired closed-loop pole sets of S3 Fig. 7 (at T = 0.15 s):
//   case1: all seven at z = 0.21          case2: all seven at z = 0.3
//   case3: one at 0.19, the other six at 0.2 (cos 68.8 deg +- j sin 68.8 deg)
//   case4: one at 0.25, the other six at 0.3 (cos 51.8 deg +- j sin 51.8 deg)
// "The other six" are three conjugate pairs at the same place (seven poles,
// one real).
#include <array>
#include <complex>
#include <cstdint>
#include <optional>
#include <string_view>

namespace tnv::fw::arsc {

enum class PoleSet : std::uint8_t { case1 = 1, case2 = 2, case3 = 3, case4 = 4 };

inline constexpr double kPaperSamplePeriod_s = 0.15;  // S3 section 3

using Poles7 = std::array<std::complex<double>, 7>;
using Poles6 = std::array<std::complex<double>, 6>;

constexpr const char* to_string(PoleSet s) noexcept {
  switch (s) {
    case PoleSet::case1: return "case1";
    case PoleSet::case2: return "case2";
    case PoleSet::case3: return "case3";
    case PoleSet::case4: return "case4";
  }
  return "?";
}
std::optional<PoleSet> parse_pole_set(std::string_view name) noexcept;

// The seven poles at T = 0.15 s; element 0 is the lone real pole.
Poles7 paper_poles(PoleSet set) noexcept;

// The same continuous-time poles at another sample period:
// z' = z^(period_s / 0.15 s) (principal branch).
Poles7 poles_at_period(const Poles7& poles, double period_s) noexcept;

// The six poles a sixth-order loop can take: all but the lone real pole
// (element 0). For case1/case2 that is six of the seven equal poles.
Poles6 six_of_seven(const Poles7& poles) noexcept;

// d* = [d1*, ..., dn*] of z^n + d1* z^{n-1} + ... + dn*, S3 eq. (23).
std::array<double, 7> desired_coefficients(const Poles7& poles) noexcept;
std::array<double, 6> desired_coefficients(const Poles6& poles) noexcept;

}  // namespace tnv::fw::arsc
