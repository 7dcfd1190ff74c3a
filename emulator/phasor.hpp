#pragma once
// A unit vector (cos a, sin a) advanced by rotation, so periodic signals cost
// a few multiplications per sub-step instead of a sin/cos.
#include <array>
#include <cmath>
#include <cstddef>

namespace tnv::emu {

struct Phasor {
  double cos_a = 1.0;
  double sin_a = 0.0;

  static Phasor at(double angle_rad) noexcept { return Phasor{std::cos(angle_rad), std::sin(angle_rad)}; }

  Phasor rotated(const Phasor& by) const noexcept {
    return Phasor{cos_a * by.cos_a - sin_a * by.sin_a, sin_a * by.cos_a + cos_a * by.sin_a};
  }
};

// Rotations by 0, a, 2a, ... (N-1)a, each from an exact sin/cos: sample i of a
// run is anchor.rotated(power[i]), so samples do not depend on each other
// (no error build-up, no serial chain).
template <std::size_t N>
std::array<Phasor, N> phasor_powers(double step_rad) noexcept {
  std::array<Phasor, N> powers{};
  for (std::size_t i = 0; i < N; ++i) powers[i] = Phasor::at(static_cast<double>(i) * step_rad);
  return powers;
}

}  // namespace tnv::emu
