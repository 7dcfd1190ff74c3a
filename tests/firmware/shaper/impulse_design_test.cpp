// Closed forms of the continuous shapers and the residual-vibration
// function they are judged with (S2 eq. (1)).
#include "firmware/shaper/impulse_design.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "firmware/shaper/residual_vibration.hpp"
#include "tests/firmware/test_units.hpp"

namespace tnv::fw {
namespace {

using test_units::kPi;

struct Expected {
  double t[4];
  double a[4];
  std::size_t n;
};

// The closed forms, written out independently of the implementation.
Expected closed_form(ShaperType type, double f, double z) {
  const double root = std::sqrt(1.0 - z * z);
  const double K = std::exp(-z * kPi / root);
  const double Td = 1.0 / (f * root);
  switch (type) {
    case ShaperType::zv: {
      const double s = 1.0 + K;
      return {{0.0, Td / 2}, {1.0 / s, K / s}, 2};
    }
    case ShaperType::zvd: {
      const double s = (1.0 + K) * (1.0 + K);
      return {{0.0, Td / 2, Td}, {1.0 / s, 2 * K / s, K * K / s}, 3};
    }
    case ShaperType::zvdd: {
      const double s = (1.0 + K) * (1.0 + K) * (1.0 + K);
      return {{0.0, Td / 2, Td, 1.5 * Td}, {1.0 / s, 3 * K / s, 3 * K * K / s, K * K * K / s}, 4};
    }
    case ShaperType::ei: {
      const double V = 0.05;
      const double a1 = (1 + V) / 4, a2 = (1 - V) / 2 * K, a3 = (1 + V) / 4 * K * K;
      const double s = a1 + a2 + a3;
      return {{0.0, Td / 2, Td}, {a1 / s, a2 / s, a3 / s}, 3};
    }
    case ShaperType::mzv: {
      const double Km = std::exp(-0.75 * z * kPi / root);
      const double a1 = 1 - 1 / std::sqrt(2.0), a2 = (std::sqrt(2.0) - 1) * Km, a3 = a1 * Km * Km;
      const double s = a1 + a2 + a3;
      return {{0.0, 0.375 * Td, 0.75 * Td}, {a1 / s, a2 / s, a3 / s}, 3};
    }
  }
  return {};
}

TEST(ImpulseDesign, AmplitudesAndTimesEqualTheirClosedForms) {
  for (ShaperType type : kShaperTypes)
    for (double f : {5.0, 12.5, 30.0, 100.0, 173.3, 200.0})
      for (double z : {0.0, 0.02, 0.05, 0.1, 0.3}) {
        const ImpulseTrain got = design_impulses(type, {f, z});
        const Expected want = closed_form(type, f, z);
        ASSERT_EQ(got.count, want.n) << to_string(type);
        for (std::size_t i = 0; i < want.n; ++i) {
          EXPECT_NEAR(got.impulse[i].t_s, want.t[i], 1e-9)
              << to_string(type) << " " << f << " Hz zeta " << z << ": time of impulse " << i << " (s)";
          EXPECT_NEAR(got.impulse[i].a, want.a[i], 1e-9)
              << to_string(type) << " " << f << " Hz zeta " << z << ": amplitude of impulse " << i;
        }
      }
}

TEST(ImpulseDesign, ZeroVibrationShapersLeaveNoneAtTheDesignPoint) {
  for (ShaperType type : {ShaperType::zv, ShaperType::zvd, ShaperType::zvdd, ShaperType::mzv})
    for (double f = 5.0; f <= 200.0; f += 6.5)
      for (double z : {0.0, 0.02, 0.05, 0.1, 0.3})
        EXPECT_LT(residual_vibration(design_impulses(type, {f, z}), f, z), 1e-12)
            << to_string(type) << " at " << f << " Hz, zeta " << z;
}

TEST(ImpulseDesign, EiLeavesItsToleranceAtTheDesignPointUndamped) {
  for (double f : {10.0, 30.0, 150.0})
    EXPECT_NEAR(residual_vibration(design_impulses(ShaperType::ei, {f, 0.0}), f, 0.0), 0.05, 1e-12) << f << " Hz";
}

// S2 eq. (1) against the textbook sensitivity curves (zeta = 0):
// ZV |cos(pi r / 2)|, ZVD cos^2, ZVDD |cos|^3, r = actual / design frequency.
TEST(ResidualVibration, MatchesTheUndampedSensitivityCurves) {
  const double f = 40.0;
  for (double r = 0.05; r < 2.0; r += 0.05) {
    const double c = std::fabs(std::cos(kPi * r / 2.0));
    EXPECT_NEAR(residual_vibration(design_impulses(ShaperType::zv, {f, 0.0}), r * f, 0.0), c, 1e-12) << "ratio " << r;
    EXPECT_NEAR(residual_vibration(design_impulses(ShaperType::zvd, {f, 0.0}), r * f, 0.0), c * c, 1e-12)
        << "ratio " << r;
    EXPECT_NEAR(residual_vibration(design_impulses(ShaperType::zvdd, {f, 0.0}), r * f, 0.0), c * c * c, 1e-12)
        << "ratio " << r;
  }
}

TEST(ResidualVibration, OneImpulseLeavesAllOfIt) {
  ImpulseTrain one;
  one.push(0.0, 1.0);
  for (double z : {0.0, 0.1}) EXPECT_NEAR(residual_vibration(one, 33.0, z), 1.0, 1e-15);
}

TEST(ResidualVibration, MoreImpulsesWidenTheFivePercentBand) {
  const double f = 30.0, z = 0.02;
  const double zv = insensitivity_band(design_impulses(ShaperType::zv, {f, z}), f, z).width();
  const double zvd = insensitivity_band(design_impulses(ShaperType::zvd, {f, z}), f, z).width();
  const double zvdd = insensitivity_band(design_impulses(ShaperType::zvdd, {f, z}), f, z).width();
  const double ei = insensitivity_band(design_impulses(ShaperType::ei, {f, z}), f, z).width();
  // Undamped: ZV 2(1 - 2 acos(0.05)/pi) = 0.064, ZVD 0.29, ZVDD 0.48.
  EXPECT_NEAR(insensitivity_band(design_impulses(ShaperType::zv, {f, 0.0}), f, 0.0).width(),
              2.0 * (1.0 - 2.0 * std::acos(0.05) / kPi), 1e-6);
  EXPECT_LT(zv, zvd);
  EXPECT_LT(zvd, zvdd);
  EXPECT_GT(ei, zvd) << "EI trades 5 % at the design point for a wider band than ZVD's";
}

TEST(ImpulseDesign, ValidationNamesTheField) {
  EXPECT_TRUE(validate(ModeSpec{30.0, 0.02}).ok);
  EXPECT_STREQ(validate(ModeSpec{std::nan(""), 0.0}).field, "freq_hz");
  EXPECT_STREQ(validate(ModeSpec{4.9, 0.0}).field, "freq_hz");
  EXPECT_STREQ(validate(ModeSpec{201.0, 0.0}).field, "freq_hz");
  EXPECT_STREQ(validate(ModeSpec{30.0, -0.01}).field, "zeta");
  EXPECT_STREQ(validate(ModeSpec{30.0, INFINITY}).field, "zeta");
  EXPECT_STREQ(validate(ModeSpec{30.0, 0.31}).field, "zeta");
}

TEST(ImpulseTrain, ConvolutionMultipliesAmplitudesAndAddsTimes) {
  const ImpulseTrain a = design_impulses(ShaperType::zv, {30.0, 0.0});
  const ImpulseTrain b = design_impulses(ShaperType::zv, {100.0, 0.0});
  const ImpulseTrain c = convolve(a, b);
  ASSERT_EQ(c.count, 4u);
  EXPECT_NEAR(c.sum(), 1.0, 1e-15);
  EXPECT_NEAR(c.impulse[1].t_s, 0.005, 1e-15);
  EXPECT_NEAR(c.impulse[2].t_s, 1.0 / 60.0, 1e-15);
  EXPECT_NEAR(c.impulse[3].t_s, 1.0 / 60.0 + 0.005, 1e-15);
  EXPECT_NEAR(c.centroid_s(), a.centroid_s() + b.centroid_s(), 1e-15) << "delays add";
}

}  // namespace
}  // namespace tnv::fw
