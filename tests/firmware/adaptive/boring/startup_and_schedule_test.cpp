// S4 eqs. (3), (10), (11): the start-up estimate, the infeed schedule and
// the bore error to deflection conversion.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "firmware/adaptive/boring/bore_measurement.hpp"
#include "firmware/adaptive/boring/infeed_schedule.hpp"
#include "firmware/adaptive/boring/startup_estimate.hpp"

namespace tnv::fw {
namespace {

double table1_d(double s, double l) { return 0.0871 * std::pow(s, 0.5025) * std::pow(l, 0.2676); }

TEST(StartupEstimate, TwoPositionsGiveEquationTenExactly) {
  const double s0 = 0.5, l1 = 40.0, l2 = 310.0, d1 = 0.17, d2 = 0.29, alpha0 = 0.7;
  const DeflectionSample samples[] = {{l1, s0, d1}, {l2, s0, d2}};
  for (BoringLogBase base : {BoringLogBase::natural, BoringLogBase::decimal}) {
    const StartupEstimate e = startup_estimate(samples, alpha0, base);
    ASSERT_TRUE(e.check.ok) << e.check.field;
    const double beta0 = std::log(d1 / d2) / std::log(l1 / l2);              // eq. (10)
    const double c0 = d1 / (std::pow(s0, alpha0) * std::pow(l1, beta0));      // eq. (10)
    EXPECT_NEAR(e.theta(2), beta0, 1e-12);
    EXPECT_NEAR(e.theta(1), alpha0, 0.0);
    EXPECT_NEAR(std::exp(e.theta(0) * ln_of_base(base)), c0, 1e-12);
    // The start-up model passes through both measurements.
    EXPECT_NEAR(model_deflection_mm(e.theta, s0, l1, base), d1, 1e-12);
    EXPECT_NEAR(model_deflection_mm(e.theta, s0, l2, base), d2, 1e-12);
  }
}

TEST(StartupEstimate, NoiselessPartOneWithTheTrueAlphaGivesTheTrueModel) {
  const DeflectionSample samples[] = {{40.0, 0.5, table1_d(0.5, 40.0)}, {175.0, 0.5, table1_d(0.5, 175.0)},
                                      {310.0, 0.5, table1_d(0.5, 310.0)}};
  const StartupEstimate e = startup_estimate(samples, 0.5025, BoringLogBase::natural);
  ASSERT_TRUE(e.check.ok);
  EXPECT_NEAR(std::exp(e.theta(0)), 0.0871, 1e-12);
  EXPECT_NEAR(e.theta(2), 0.2676, 1e-12);
}

TEST(StartupEstimate, RefusesWhatEquationTenCannotUse) {
  const DeflectionSample one[] = {{40.0, 0.5, 0.1}};
  EXPECT_STREQ(startup_estimate(one, 0.5, BoringLogBase::natural).check.field, "measurements");
  const DeflectionSample same_l[] = {{40.0, 0.5, 0.1}, {40.0, 0.5, 0.12}};
  EXPECT_STREQ(startup_estimate(same_l, 0.5, BoringLogBase::natural).check.field, "overhang_mm");
  const DeflectionSample negative[] = {{40.0, 0.5, -0.01}, {310.0, 0.5, 0.2}};
  EXPECT_STREQ(startup_estimate(negative, 0.5, BoringLogBase::natural).check.field, "deflection_mm");
  const DeflectionSample nan_s[] = {{40.0, std::nan(""), 0.1}, {310.0, 0.5, 0.2}};
  EXPECT_STREQ(startup_estimate(nan_s, 0.5, BoringLogBase::natural).check.field, "infeed_mm_rev");
}

TEST(InfeedSchedule, EquationThreeGivesTheTargetDeflectionAlongTheBore) {
  const BoringPlannerParams p;
  const BoringTheta theta(std::log(0.0871), 0.5025, 0.2676);
  for (double l = 40.0; l <= 310.0; l += 10.0) {
    const InfeedCommand cmd = optimal_infeed(theta, l, p);
    ASSERT_TRUE(cmd.check.ok);
    EXPECT_FALSE(cmd.infeed_limited);
    EXPECT_NEAR(table1_d(cmd.infeed_mm_rev, l), p.target_deflection_mm, 1e-12) << "L = " << l << " mm";
    const double closed_form = std::pow(p.target_deflection_mm / (0.0871 * std::pow(l, 0.2676)), 1.0 / 0.5025);
    EXPECT_NEAR(cmd.infeed_mm_rev, closed_form, 1e-12);
  }
  BoringPlannerParams decimal = p;
  decimal.log_base = BoringLogBase::decimal;
  const BoringTheta theta10(std::log10(0.0871), 0.5025, 0.2676);
  EXPECT_NEAR(optimal_infeed(theta10, 100.0, decimal).infeed_mm_rev, optimal_infeed(theta, 100.0, p).infeed_mm_rev, 1e-12);
}

TEST(InfeedSchedule, ClampsToTheInfeedRangeAndHoldsAlphaAboveItsFloor) {
  BoringPlannerParams p;
  const InfeedCommand fast = optimal_infeed(BoringTheta(std::log(0.001), 0.5, 0.2), 100.0, p);
  EXPECT_TRUE(fast.infeed_limited);
  EXPECT_DOUBLE_EQ(fast.infeed_mm_rev, p.infeed_max_mm_rev);
  const InfeedCommand slow = optimal_infeed(BoringTheta(std::log(5.0), 0.5, 0.2), 100.0, p);
  EXPECT_TRUE(slow.infeed_limited);
  EXPECT_DOUBLE_EQ(slow.infeed_mm_rev, p.infeed_min_mm_rev);
  const InfeedCommand tiny_alpha = optimal_infeed(BoringTheta(std::log(0.0871), 1e-6, 0.2676), 100.0, p);
  EXPECT_TRUE(tiny_alpha.alpha_limited);
  EXPECT_TRUE(std::isfinite(tiny_alpha.infeed_mm_rev));
  const InfeedCommand negative_alpha = optimal_infeed(BoringTheta(std::log(0.0871), -0.3, 0.2676), 100.0, p);
  EXPECT_TRUE(negative_alpha.alpha_limited);
  EXPECT_GE(negative_alpha.infeed_mm_rev, p.infeed_min_mm_rev);
  EXPECT_LE(negative_alpha.infeed_mm_rev, p.infeed_max_mm_rev);
}

TEST(InfeedSchedule, RefusesNonFiniteOrOutOfRangeInputsWithZeroInfeed) {
  const BoringPlannerParams p;
  const BoringTheta theta(std::log(0.0871), 0.5025, 0.2676);
  for (double l : {std::nan(""), std::numeric_limits<double>::infinity(), 39.9, 310.1, -50.0}) {
    const InfeedCommand cmd = optimal_infeed(theta, l, p);
    EXPECT_FALSE(cmd.check.ok) << "L = " << l;
    EXPECT_STREQ(cmd.check.field, "overhang_mm");
    EXPECT_EQ(cmd.infeed_mm_rev, 0.0) << "a refused command must not be cut";
  }
  const InfeedCommand bad_theta = optimal_infeed(BoringTheta(std::nan(""), 0.5, 0.2), 100.0, p);
  EXPECT_STREQ(bad_theta.check.field, "theta");
  EXPECT_EQ(bad_theta.infeed_mm_rev, 0.0);
}

TEST(BoreMeasurement, EquationElevenAndItsInverse) {
  // phi = 60 deg: 2 cos phi = 1, a 0.02 mm undersize is 0.02 mm of extra deflection.
  EXPECT_NEAR(deflection_from_bore_error_mm(0.02, 0.1165, 60.0), 0.1365, 1e-12);
  EXPECT_NEAR(deflection_from_bore_error_mm(-0.03, 0.1165, 60.0), 0.0865, 1e-12);
  // phi = 0: the deflection is radial, the diameter changes by twice as much.
  EXPECT_NEAR(deflection_from_bore_error_mm(0.02, 0.1, 0.0), 0.11, 1e-12);
  for (double phi : {0.0, 30.0, 60.0, 80.0})
    EXPECT_NEAR(deflection_from_bore_error_mm(bore_error_from_deflection_mm(0.123, 0.1165, phi), 0.1165, phi), 0.123,
                1e-12);
}

}  // namespace
}  // namespace tnv::fw
