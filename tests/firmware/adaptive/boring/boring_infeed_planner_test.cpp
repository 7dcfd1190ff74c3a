// The S4 planner as a whole: start-up, schedule, RLS, variance
// perturbation, validation.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <type_traits>

#include "firmware/adaptive/boring/boring_infeed_planner.hpp"

namespace tnv::fw {
namespace {

// Fixed size: the estimate and P are compile-time 3 and 3x3 (Eigen never
// allocates those), the rest is plain values. (bench_boring counts heap
// allocations per part: 0.)
static_assert(BoringTheta::SizeAtCompileTime == 3 && BoringCovariance::SizeAtCompileTime == 9);
static_assert(std::is_trivially_destructible_v<VariancePerturbation>);
static_assert(noexcept(std::declval<BoringInfeedPlanner&>().record_part({})));
static_assert(noexcept(std::declval<const BoringInfeedPlanner&>().infeed(100.0)));

struct TrueSet {
  double c_mm, alpha, beta;
  double d(double s, double l) const { return c_mm * std::pow(s, alpha) * std::pow(l, beta); }
};
constexpr TrueSet kTable1{0.0871, 0.5025, 0.2676};
constexpr double kL1 = 40.0, kL2 = 310.0;

// Plans, "cuts" (noiseless plus the given deflection error), records.
BoringPartReport cut_part(BoringInfeedPlanner& planner, const TrueSet& set, double error1_mm = 0.0,
                          double error2_mm = 0.0) {
  const BoringPlannerParams& p = planner.params();
  BoreMeasurement m[2];
  const double errors[2] = {error1_mm, error2_mm};
  const double ls[2] = {kL1, kL2};
  for (int i = 0; i < 2; ++i) {
    const InfeedCommand cmd = planner.infeed(ls[i]);
    EXPECT_TRUE(cmd.check.ok);
    const double d = set.d(cmd.infeed_mm_rev, ls[i]) + errors[i];
    m[i] = {ls[i], cmd.infeed_mm_rev, bore_error_from_deflection_mm(d, p.target_deflection_mm, p.force_angle_deg)};
  }
  return planner.record_part(m);
}

TEST(BoringInfeedPlanner, PartOneIsCutAtTheNominalInfeedThenEquationTenStartsThePlanner) {
  BoringInfeedPlanner planner;
  ASSERT_TRUE(planner.configured());
  EXPECT_FALSE(planner.started());
  EXPECT_DOUBLE_EQ(planner.infeed(kL1).infeed_mm_rev, 0.5);
  EXPECT_DOUBLE_EQ(planner.infeed(kL2).infeed_mm_rev, 0.5);
  const BoringPartReport r = cut_part(planner, kTable1);
  ASSERT_TRUE(r.check.ok) << r.check.field << ": " << r.check.reason;
  EXPECT_TRUE(r.startup);
  EXPECT_TRUE(planner.started());
  EXPECT_EQ(r.rls_updates, 0) << "default: part 1 only feeds eq. (10)";
  EXPECT_EQ(planner.covariance(), BoringCovariance::Identity()) << "P0 = I";
  EXPECT_NEAR(planner.estimated_beta(), kTable1.beta, 1e-12) << "noiseless eq. (10)";
  EXPECT_DOUBLE_EQ(planner.estimated_alpha(), 0.5);
}

TEST(BoringInfeedPlanner, NoiselessStartWithTheTrueAlphaCutsEveryPartAtTheTargetDeflection) {
  BoringPlannerParams p;
  p.alpha0 = kTable1.alpha;
  BoringInfeedPlanner planner(p);
  cut_part(planner, kTable1);
  for (int part = 2; part <= 20; ++part) {
    for (double l : {kL1, 100.0, 200.0, kL2}) {
      const double s = planner.infeed(l).infeed_mm_rev;
      EXPECT_NEAR(kTable1.d(s, l), p.target_deflection_mm, 1e-9) << "part " << part << ", L = " << l << " mm";
    }
    const BoringPartReport r = cut_part(planner, kTable1);
    EXPECT_EQ(r.out_of_band, 0);
    EXPECT_EQ(r.rls_updates, 2);
  }
  EXPECT_EQ(planner.resets(), 0);
}

TEST(BoringInfeedPlanner, ThreeOutOfBandMeasurementsInARowResetTheCovariance) {
  BoringInfeedPlanner planner;
  cut_part(planner, kTable1);
  for (int part = 2; part <= 6; ++part) cut_part(planner, kTable1);
  const BoringCovariance shrunk = planner.covariance();
  EXPECT_LT(shrunk.trace(), 0.6 * 3.0) << "ten updates shrink P0 = I (trace 3)";
  const double far = 4.0 * planner.band_half_width_mm();
  BoringPartReport r = cut_part(planner, kTable1, far, far);
  EXPECT_EQ(r.out_of_band, 2);
  EXPECT_FALSE(r.reset) << "two in a row";
  EXPECT_EQ(planner.streak(), 2);
  r = cut_part(planner, kTable1, far, 0.0);
  EXPECT_TRUE(r.reset) << "the third in a row";
  EXPECT_EQ(planner.resets(), 1);
  EXPECT_GT(planner.covariance().trace(), shrunk.trace()) << "P = I, then two updates";
}

TEST(BoringInfeedPlanner, PartCountingResetsAfterThreeBadPartsAtTheEndOfThePart) {
  BoringPlannerParams p;
  p.reset_count = BoringResetCount::parts;
  BoringInfeedPlanner planner(p);
  cut_part(planner, kTable1);
  const double far = 4.0 * planner.band_half_width_mm();
  EXPECT_FALSE(cut_part(planner, kTable1, 0.0, far).reset);
  EXPECT_FALSE(cut_part(planner, kTable1, far, 0.0).reset);
  EXPECT_TRUE(cut_part(planner, kTable1, 0.0, far).reset);
  EXPECT_EQ(planner.covariance(), BoringCovariance::Identity()) << "reset after the part's updates";
}

TEST(BoringInfeedPlanner, GainFormsPutSigmaWhereTheyArePrinted) {
  BoringPlannerParams p;
  p.sigma_d_mm = 0.005;
  const double sigma = std::pow(0.005 / 0.1165, 2);
  p.gain_form = BoringGainForm::normalised;
  BoringInfeedPlanner n(p);
  EXPECT_DOUBLE_EQ(n.gain_denominator_5(), 1.0);
  EXPECT_DOUBLE_EQ(n.gain_denominator_6(), 1.0);
  p.gain_form = BoringGainForm::kalman;
  BoringInfeedPlanner k(p);
  EXPECT_NEAR(k.gain_denominator_5(), sigma, 1e-15);
  EXPECT_NEAR(k.gain_denominator_6(), sigma, 1e-15);
  p.gain_form = BoringGainForm::printed;
  BoringInfeedPlanner pr(p);
  EXPECT_NEAR(pr.gain_denominator_5(), sigma, 1e-15);
  EXPECT_DOUBLE_EQ(pr.gain_denominator_6(), 1.0);
  p.log_base = BoringLogBase::decimal;
  BoringInfeedPlanner dec(p);
  EXPECT_NEAR(dec.noise_variance(), sigma / std::pow(std::log(10.0), 2), 1e-15) << "Var(log10 d)";
}

TEST(BoringInfeedPlanner, ANonPositiveDeflectionIsOutOfBandButNotFitted) {
  BoringInfeedPlanner planner;
  cut_part(planner, kTable1);
  const BoringTheta before = planner.theta();
  BoreMeasurement m[2] = {{kL1, 0.25, bore_error_from_deflection_mm(-0.01, 0.1165, 60.0)},
                          {kL2, 0.08, bore_error_from_deflection_mm(0.1165, 0.1165, 60.0)}};
  const BoringPartReport r = planner.record_part(m);
  ASSERT_TRUE(r.check.ok);
  EXPECT_EQ(r.skipped, 1);
  EXPECT_EQ(r.rls_updates, 1);
  EXPECT_EQ(r.out_of_band, 1);
  EXPECT_NE(planner.theta(), before);
}

TEST(BoringInfeedPlanner, InvalidMeasurementsAreRefusedWholeNamingTheField) {
  BoringInfeedPlanner planner;
  cut_part(planner, kTable1);
  cut_part(planner, kTable1, 0.01, -0.01);
  const BoringTheta theta = planner.theta();
  const BoringCovariance p = planner.covariance();
  const int parts = planner.parts_recorded();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    BoreMeasurement second;
    const char* field;
  };
  for (const Case& c : {Case{{kL2, 0.08, nan}, "bore_error_mm"}, Case{{kL2, nan, 0.0}, "infeed_mm_rev"},
                        Case{{kL2, -0.08, 0.0}, "infeed_mm_rev"}, Case{{nan, 0.08, 0.0}, "overhang_mm"},
                        Case{{400.0, 0.08, 0.0}, "overhang_mm"}, Case{{10.0, 0.08, 0.0}, "overhang_mm"}}) {
    const BoreMeasurement m[2] = {{kL1, 0.25, 0.05}, c.second};  // the first one is fine, and far out of band
    const BoringPartReport r = planner.record_part(m);
    EXPECT_FALSE(r.check.ok);
    EXPECT_STREQ(r.check.field, c.field);
    EXPECT_EQ(planner.theta(), theta) << c.field << ": nothing half-applied";
    EXPECT_EQ(planner.covariance(), p);
    EXPECT_EQ(planner.parts_recorded(), parts);
    EXPECT_EQ(planner.streak(), 0) << "the out-of-band first measurement was not counted";
  }
  EXPECT_STREQ(planner.record_part({}).check.field, "measurements");
  BoreMeasurement nine[9];
  for (BoreMeasurement& m : nine) m = {100.0, 0.1, 0.0};
  EXPECT_STREQ(planner.record_part(nine).check.field, "measurements");
}

TEST(BoringInfeedPlanner, StartUpNeedsTwoOverhangs) {
  BoringInfeedPlanner planner;
  const BoreMeasurement one[1] = {{kL1, 0.5, 0.05}};
  EXPECT_STREQ(planner.record_part(one).check.field, "measurements");
  const BoreMeasurement same[2] = {{kL1, 0.5, 0.05}, {kL1, 0.5, 0.06}};
  EXPECT_STREQ(planner.record_part(same).check.field, "overhang_mm");
  EXPECT_FALSE(planner.started());
}

TEST(BoringInfeedPlanner, InvalidParamsLeaveItUnconfiguredOrUnchanged) {
  BoringPlannerParams bad;
  bad.sigma_d_mm = std::numeric_limits<double>::infinity();
  BoringInfeedPlanner unconfigured(bad);
  EXPECT_FALSE(unconfigured.configured());
  EXPECT_STREQ(unconfigured.config_status().field, "sigma_d_mm");
  EXPECT_FALSE(unconfigured.infeed(100.0).check.ok);
  const BoreMeasurement m[2] = {{kL1, 0.5, 0.05}, {kL2, 0.5, 0.1}};
  EXPECT_FALSE(unconfigured.record_part(m).check.ok);

  BoringInfeedPlanner planner;
  cut_part(planner, kTable1);
  bad = planner.params();
  bad.alpha0 = 0.0;
  EXPECT_STREQ(planner.set_params(bad).field, "alpha0");
  EXPECT_TRUE(planner.started()) << "a refused set changes nothing";
  EXPECT_DOUBLE_EQ(planner.params().alpha0, 0.5);
}

TEST(BoringPlannerParams, DefaultsAreThePapersAndValid) {
  const BoringPlannerParams p;
  EXPECT_TRUE(validate(p).ok);
  EXPECT_EQ(p.target_deflection_mm, 0.1165);
  EXPECT_EQ(p.sigma_d_mm, 0.016231);
  EXPECT_EQ(p.gain_form, BoringGainForm::normalised);
  EXPECT_EQ(p.reset_count, BoringResetCount::measurements);
  EXPECT_EQ(p.reset_after, 3);
}

TEST(BoringPlannerParams, EveryNonFiniteFieldIsNamed) {
  using Member = double BoringPlannerParams::*;
  const std::pair<Member, const char*> fields[] = {
      {&BoringPlannerParams::target_deflection_mm, "target_deflection_mm"},
      {&BoringPlannerParams::sigma_d_mm, "sigma_d_mm"},
      {&BoringPlannerParams::band_sigmas, "band_sigmas"},
      {&BoringPlannerParams::alpha0, "alpha0"},
      {&BoringPlannerParams::nominal_infeed_mm_rev, "nominal_infeed_mm_rev"},
      {&BoringPlannerParams::infeed_min_mm_rev, "infeed_min_mm_rev"},
      {&BoringPlannerParams::infeed_max_mm_rev, "infeed_max_mm_rev"},
      {&BoringPlannerParams::overhang_min_mm, "overhang_min_mm"},
      {&BoringPlannerParams::overhang_max_mm, "overhang_max_mm"},
      {&BoringPlannerParams::alpha_min, "alpha_min"},
      {&BoringPlannerParams::initial_covariance, "initial_covariance"},
      {&BoringPlannerParams::force_angle_deg, "force_angle_deg"}};
  for (const auto& [member, name] : fields)
    for (double v : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
      BoringPlannerParams p;
      p.*member = v;
      const ParamCheck c = validate(p);
      EXPECT_FALSE(c.ok) << name;
      EXPECT_STREQ(c.field, name);
    }
}

TEST(BoringPlannerParams, OutOfRangeValuesAreNamed) {
  const auto field_of = [](auto mutate) {
    BoringPlannerParams p;
    mutate(p);
    return std::string(validate(p).field);
  };
  EXPECT_EQ(field_of([](auto& p) { p.target_deflection_mm = 0.0; }), "target_deflection_mm");
  EXPECT_EQ(field_of([](auto& p) { p.sigma_d_mm = -0.01; }), "sigma_d_mm");
  EXPECT_EQ(field_of([](auto& p) { p.alpha0 = 3.5; }), "alpha0");
  EXPECT_EQ(field_of([](auto& p) { p.infeed_max_mm_rev = p.infeed_min_mm_rev; }), "infeed_max_mm_rev");
  EXPECT_EQ(field_of([](auto& p) { p.nominal_infeed_mm_rev = 2.0; }), "nominal_infeed_mm_rev");
  EXPECT_EQ(field_of([](auto& p) { p.overhang_max_mm = 30.0; }), "overhang_max_mm");
  EXPECT_EQ(field_of([](auto& p) { p.force_angle_deg = 90.0; }), "force_angle_deg");
  EXPECT_EQ(field_of([](auto& p) { p.reset_after = 0; }), "reset_after");
  EXPECT_EQ(field_of([](auto& p) { p.gain_form = static_cast<BoringGainForm>(7); }), "gain_form");
  EXPECT_EQ(field_of([](auto& p) { p.reset_count = static_cast<BoringResetCount>(7); }), "reset_count");
}

}  // namespace
}  // namespace tnv::fw
