#include "emulator/structural_mode.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "emulator/substep_timing.hpp"

namespace tnv::emu {
namespace {

TEST(StructuralMode, OffByDefaultHasNoDeflection) {
  StructuralMode mode(0.0, 0.0, kSubstep_s);
  EXPECT_FALSE(mode.enabled());
  for (int i = 0; i < 100; ++i) mode.step(1000.0);
  EXPECT_EQ(mode.deflection_mm(), 0.0);
}

TEST(StructuralMode, StepResponseIsExact) {
  const double f_hz = 30.0, zeta = 0.02, accel_mm_s2 = 500.0;
  StructuralMode mode(f_hz, zeta, kSubstep_s);
  const double w = 2.0 * std::numbers::pi * f_hz;
  const double sigma = zeta * w, wd = w * std::sqrt(1.0 - zeta * zeta);
  for (int k = 1; k <= 5'000; ++k) {
    mode.step(accel_mm_s2);
    if (k % 250 != 0) continue;
    const double t = k * kSubstep_s;
    // x'' + 2 zeta w x' + w^2 x = -a from rest
    const double x = -accel_mm_s2 / (w * w) *
                     (1.0 - std::exp(-sigma * t) * (std::cos(wd * t) + sigma / wd * std::sin(wd * t)));
    ASSERT_NEAR(mode.deflection_mm(), x, 1e-12) << "deflection (mm) at t = " << t << " s";
  }
}

TEST(StructuralMode, RingsAtTheDampedFrequency) {
  const double f_hz = 100.0, zeta = 0.02;
  StructuralMode mode(f_hz, zeta, kSubstep_s);
  mode.set_state(1e-3, 0.0);
  int crossings = 0;
  double previous = mode.deflection_mm();
  for (int k = 0; k < 100'000; ++k) {  // 1 s
    mode.step(0.0);
    if ((mode.deflection_mm() > 0.0) != (previous > 0.0)) ++crossings;
    previous = mode.deflection_mm();
  }
  const double fd_hz = f_hz * std::sqrt(1.0 - zeta * zeta);
  EXPECT_NEAR(crossings / 2.0, fd_hz, 1.0) << "oscillation frequency, Hz";
}

}  // namespace
}  // namespace tnv::emu
