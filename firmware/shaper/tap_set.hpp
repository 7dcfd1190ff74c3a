#pragma once
// A shaper as implemented on the control grid: amplitudes a_j at whole
// sample delays k_j (sparse, sorted by k, no two equal k). Fixed capacity:
// two single-mode shapers of up to 16 taps convolved.
#include <array>
#include <cstddef>
#include <cstdint>

namespace tnv::fw {

struct Tap {
  std::uint32_t k = 0;  // delay in samples
  double a = 0.0;
};

struct TapSet {
  static constexpr std::size_t kCapacity = 256;
  std::array<Tap, kCapacity> tap{};
  std::size_t count = 0;

  // The identity shaper: one tap of 1 at delay 0.
  static TapSet identity() noexcept {
    TapSet t;
    t.tap[0] = {0, 1.0};
    t.count = 1;
    return t;
  }
  // Adds a to the tap at delay k (kept sorted); false when full.
  bool add(std::uint32_t k, double a) noexcept;
  std::uint32_t span() const noexcept { return count == 0 ? 0 : tap[count - 1].k; }  // longest delay
  double sum() const noexcept {
    double s = 0.0;
    for (std::size_t i = 0; i < count; ++i) s += tap[i].a;
    return s;
  }
  // Centroid in samples: sum(a_j k_j) / sum(a_j).
  double centroid_samples() const noexcept {
    double m = 0.0;
    for (std::size_t i = 0; i < count; ++i) m += tap[i].a * static_cast<double>(tap[i].k);
    return m / sum();
  }
  bool is_identity() const noexcept { return count == 1 && tap[0].k == 0 && tap[0].a == 1.0; }
};

// Two grid shapers in series (multi-mode): the product of their z-polynomials.
// Two shapers of up to 16 taps always fit.
TapSet convolve(const TapSet& a, const TapSet& b) noexcept;

}  // namespace tnv::fw
