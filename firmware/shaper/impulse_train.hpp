#pragma once
// A continuous-time impulse sequence: amplitudes A_i at times t_i (the
// shaper as designed, before it meets the 1 ms grid). Fixed capacity:
// two 4-impulse shapers convolved.
#include <array>
#include <cstddef>

namespace tnv::fw {

struct Impulse {
  double t_s = 0.0;
  double a = 0.0;
};

struct ImpulseTrain {
  static constexpr std::size_t kCapacity = 16;
  std::array<Impulse, kCapacity> impulse{};
  std::size_t count = 0;

  // Requires count < kCapacity (callers size their designs to fit).
  void push(double t_s, double a) noexcept {
    if (count < kCapacity) impulse[count++] = {t_s, a};
  }
  double duration_s() const noexcept { return count == 0 ? 0.0 : impulse[count - 1].t_s; }
  double sum() const noexcept {
    double s = 0.0;
    for (std::size_t i = 0; i < count; ++i) s += impulse[i].a;
    return s;
  }
  // Centroid sum(A_i t_i) / sum(A_i): the delay the shaper adds to a ramp.
  double centroid_s() const noexcept {
    double m = 0.0;
    for (std::size_t i = 0; i < count; ++i) m += impulse[i].a * impulse[i].t_s;
    return m / sum();
  }
};

// Two shapers in series (multi-mode shaping): every pair of impulses,
// times added and amplitudes multiplied, sorted by time, equal times merged.
ImpulseTrain convolve(const ImpulseTrain& a, const ImpulseTrain& b) noexcept;

}  // namespace tnv::fw
