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

// Near its cutoff the curve skips exp() where the Stribeck term cannot move
// f_c's last bit: it must give the bits of the formula evaluated in full.
TEST(StribeckFriction, SkippingExpNearTheCutoffGivesTheSameBits) {
  struct Curve {
    double coulomb_mm_s, stiction_mm_s, stribeck_mm_s;
  };
  // f_c just below a power of two has the least room under half an ulp.
  for (const Curve c : {Curve{1.5, 3.0, 0.1}, Curve{2.0, 4.0, 0.1}, Curve{std::nextafter(2.0, 0.0), 2.5, 0.05},
                        Curve{1.0, 300.0, 0.2}, Curve{0.7, 0.75, 0.1}}) {
    const StribeckFriction f(c.coulomb_mm_s, c.stiction_mm_s, c.stribeck_mm_s);
    const double inv_stribeck_s_mm = 1.0 / c.stribeck_mm_s;
    for (double ratio = 4.0; ratio <= 8.0; ratio += 1.0 / 4096.0) {
      const double v = ratio * c.stribeck_mm_s;
      const double r = v * inv_stribeck_s_mm;
      const double full = c.coulomb_mm_s + (c.stiction_mm_s - c.coulomb_mm_s) * std::exp(-r * r);
      ASSERT_EQ(f.magnitude_mm_s(v), full) << "f_c " << c.coulomb_mm_s << ", v/v_s " << ratio;
      ASSERT_EQ(f.magnitude_mm_s(-v), full) << "f_c " << c.coulomb_mm_s << ", v/v_s " << -ratio;
    }
  }
}

TEST(StribeckFriction, PureStictionCurveHasNoEarlyCutoff) {
  const StribeckFriction f(0.0, 3.0, 0.1);
  EXPECT_GT(f.slipping_mm_s(0.7), 0.0) << "with f_c = 0 the Stribeck term is all there is";
  EXPECT_DOUBLE_EQ(f.slipping_mm_s(0.7), 3.0 * std::exp(-49.0));
}

}  // namespace
}  // namespace tnv::emu
