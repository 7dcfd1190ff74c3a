#include "emulator/stribeck_friction.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tnv::emu {
namespace {

// reference plant defaults: f_c = 1.5, f_s = 3.0, v_s = 0.1 mm/s
double reference(double v) {
  if (v == 0.0) return 0.0;
  return std::copysign(1.5 + 1.5 * std::exp(-(v / 0.1) * (v / 0.1)), v);
}

TEST(StribeckFriction, MatchesTheCurveAtSeveralSpeeds) {
  const StribeckFriction f(1.5, 3.0, 0.1);
  for (double v : {1e-6, 0.01, 0.05, 0.1, 0.2, 0.5, 0.649, 0.651, 1.0, 10.0}) {
    EXPECT_DOUBLE_EQ(f.slipping_mm_s(v), reference(v)) << "at v = " << v << " mm/s";
    EXPECT_DOUBLE_EQ(f.slipping_mm_s(-v), -reference(v)) << "at v = " << -v << " mm/s";
  }
  EXPECT_NEAR(f.slipping_mm_s(0.1), 1.5 + 1.5 / std::exp(1.0), 1e-15);
  EXPECT_EQ(f.slipping_mm_s(1.0), 1.5) << "far above v_s the curve is exactly f_c";
  EXPECT_EQ(f.slipping_mm_s(0.0), 0.0);
}

TEST(StribeckFriction, CutoffIsSeamless) {
  const StribeckFriction f(1.5, 3.0, 0.1);
  const double edge = 0.65;
  EXPECT_EQ(f.slipping_mm_s(std::nextafter(edge, 0.0)), 1.5);
  EXPECT_EQ(f.slipping_mm_s(edge), 1.5);
}

TEST(StribeckFriction, PureStictionCurveHasNoEarlyCutoff) {
  const StribeckFriction f(0.0, 3.0, 0.1);
  EXPECT_GT(f.slipping_mm_s(0.7), 0.0) << "with f_c = 0 the Stribeck term is all there is";
  EXPECT_DOUBLE_EQ(f.slipping_mm_s(0.7), 3.0 * std::exp(-49.0));
}

}  // namespace
}  // namespace tnv::emu
