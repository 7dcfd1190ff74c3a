#include "emulator/structural_mode.hpp"

#include <cmath>
#include <numbers>

namespace tnv::emu {

StructuralMode::StructuralMode(double mode_hz, double zeta, double step_s) noexcept : enabled_(mode_hz > 0.0) {
  if (!enabled_) return;
  // Long double once at construction: 1 - phi11 ~ (w h)^2 / 2 is a small
  // difference of numbers near 1.
  using ld = long double;
  const ld w = 2.0L * std::numbers::pi_v<ld> * static_cast<ld>(mode_hz);
  const ld sigma = static_cast<ld>(zeta) * w;
  const ld wd = w * std::sqrt(1.0L - static_cast<ld>(zeta) * static_cast<ld>(zeta));  // validated zeta < 1
  const ld h = static_cast<ld>(step_s);
  const ld e = std::exp(-sigma * h);
  const ld c = std::cos(wd * h);
  const ld s = std::sin(wd * h);
  // e^{A h} for A = [0 1; -w^2 -2 zeta w] (underdamped closed form)
  const ld p11 = e * (c + sigma / wd * s);
  const ld p12 = e * s / wd;
  const ld p21 = -e * w * w / wd * s;
  const ld p22 = e * (c - sigma / wd * s);
  // Constant input -a: equilibrium x_ss = -a / w^2, so
  // x(h) = phi11 x + phi12 x' - (1 - phi11) a / w^2,  x'(h) = phi21 x + phi22 x' + phi21 a / w^2.
  phi11_ = static_cast<double>(p11);
  phi12_ = static_cast<double>(p12);
  phi21_ = static_cast<double>(p21);
  phi22_ = static_cast<double>(p22);
  gamma1_ = static_cast<double>(-(1.0L - p11) / (w * w));
  gamma2_ = static_cast<double>(p21 / (w * w));
  two_zeta_w_ = static_cast<double>(2.0L * sigma);
  w2_ = static_cast<double>(w * w);
}

}  // namespace tnv::emu
