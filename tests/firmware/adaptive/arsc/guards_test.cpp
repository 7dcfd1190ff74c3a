// The guards of the gain update fire on the singular cases of issue 8 and
// the controller keeps its last good gains with a reason.
#include <gtest/gtest.h>

#include <random>

#include "firmware/adaptive/arsc/faithful_arsc.hpp"
#include "firmware/adaptive/arsc/faithful_gain_solve.hpp"
#include "firmware/adaptive/arsc/pole_sets.hpp"
#include "firmware/adaptive/arsc/robust_arsc.hpp"
#include "tests/firmware/adaptive/arsc/arsc_test_models.hpp"

namespace tnv::fw::arsc {
namespace {

// d* whose d1* gives the wanted gamma01 through eq. (25), the rest from case1.
std::array<double, 7> d_star_for_gamma01(const Arv2Model& m, double gamma01, const FixedGains& f) {
  auto d = desired_coefficients(paper_poles(PoleSet::case1));
  d[0] = m.phi1(0, 0) + m.phi1(1, 1) - 1.0 - f.gamma03 - gamma01;
  return d;
}

TEST(ArscGuards, Case2AtThePaperStartingEstimatesIsSingular) {
  const auto d = desired_coefficients(paper_poles(PoleSet::case2));
  const GainDesign g = solve_faithful_gains(paper_initial_model(), d, FixedGains{}, GuardLimits{});
  EXPECT_NEAR(fig3_system(paper_initial_model(), d, FixedGains{}).gamma01, 0.6, 1e-12);
  EXPECT_EQ(g.reason, GuardReason::ill_conditioned) << "rcond " << g.rcond;
  EXPECT_LT(g.rcond, 1e-12);
}

TEST(ArscGuards, Gamma01AtOneOrAtTheFixedGainRatioIsSingularForEveryModel) {
  std::mt19937 rng(7);
  const FixedGains f{};
  const double ratio_point = f.gamma03 + f.gamma41 * f.gamma02 / f.gamma42;  // 0.6
  for (int trial = 0; trial < 50; ++trial) {
    const Arv2Model m = test::random_stable_model(rng);
    for (double gamma01 : {1.0, ratio_point}) {
      const GainDesign g = solve_faithful_gains(m, d_star_for_gamma01(m, gamma01, f), f, GuardLimits{});
      EXPECT_EQ(g.reason, GuardReason::ill_conditioned) << "gamma01 " << gamma01 << " rcond " << g.rcond;
    }
    // ... and a little away from both it is not.
    const GainDesign ok = solve_faithful_gains(m, d_star_for_gamma01(m, 0.3, f), f, GuardLimits{});
    EXPECT_NE(ok.reason, GuardReason::ill_conditioned) << "rcond " << ok.rcond;
  }
}

TEST(ArscGuards, EveryExactArv2FitOfTheS3ProcessIsSingular) {
  // The process model itself (Phi2 = 0, theta01 = 0) and members of the
  // exact-fit family (I + C q^-1)(I + Phi1 q^-1), C theta0 = 0.
  const std::array<double, 7> d = desired_coefficients(paper_poles(PoleSet::case1));
  for (double delta : {0.2, 0.6, 1.0}) {
    const Arv2Model base = test::s3_process_model(delta);
    EXPECT_EQ(solve_faithful_gains(base, d, FixedGains{}, GuardLimits{}).reason, GuardReason::ill_conditioned)
        << "depth " << delta;
    for (const auto& c : {std::pair{0.2, -0.1}, std::pair{-0.15, 0.25}}) {
      Eigen::Matrix2d cm;
      cm << c.first, 0.0, c.second, 0.0;
      Arv2Model fit = base;
      fit.phi1 = base.phi1 + cm;
      fit.phi2 = cm * base.phi1;
      const GainDesign g = solve_faithful_gains(fit, d, FixedGains{}, GuardLimits{});
      EXPECT_TRUE(g.reason == GuardReason::ill_conditioned || g.reason == GuardReason::model_unstable)
          << "depth " << delta << ": " << to_string(g.reason) << " rcond " << g.rcond;
    }
  }
}

TEST(ArscGuards, ModelChecksNameTheirReason) {
  const auto d = desired_coefficients(paper_poles(PoleSet::case1));
  Arv2Model m = paper_initial_model();
  m.theta0.setZero();
  EXPECT_EQ(solve_faithful_gains(m, d, FixedGains{}, GuardLimits{}).reason, GuardReason::theta0_zero);
  m = paper_initial_model();
  m.phi1 << 0.2, 0.4, 0.1, 0.2;  // rank 1
  EXPECT_EQ(solve_faithful_gains(m, d, FixedGains{}, GuardLimits{}).reason, GuardReason::phi1_rank);
  m = paper_initial_model();
  m.phi2 << 1.2, 0.0, 0.0, 0.9;  // |d4| > 1
  EXPECT_EQ(solve_faithful_gains(m, d, FixedGains{}, GuardLimits{}).reason, GuardReason::model_unstable);
  m = paper_initial_model();
  m.phi1(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(solve_faithful_gains(m, d, FixedGains{}, GuardLimits{}).reason, GuardReason::model_not_finite);
}

TEST(ArscGuards, FaithfulLoopHoldsOutputAtZeroUntilItHasGains) {
  FaithfulArscConfig c;
  c.d_star = desired_coefficients(paper_poles(PoleSet::case2));
  ASSERT_TRUE(validate(c).ok);
  FaithfulArsc arsc(c);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(arsc.step(0.0, 0.0), 0.0);
  EXPECT_FALSE(arsc.signals().have_gains);
  EXPECT_EQ(arsc.signals().last_reason, GuardReason::ill_conditioned);
  EXPECT_EQ(arsc.signals().reason_counts[static_cast<std::size_t>(GuardReason::ill_conditioned)], 5u);
}

TEST(ArscGuards, RobustLoopKeepsTheLastGoodGainsWhenAnUpdateIsRefused) {
  RobustArscConfig c;
  c.d_star = desired_coefficients(six_of_seven(paper_poles(PoleSet::case1)));
  c.estimator.initial_gain = 0.5;
  c.estimator.forgetting = 0.05;
  // A bound the design at g = 0.5 meets but a much smaller g (larger gains) does not.
  c.limits.max_gain = 8.0;
  ASSERT_TRUE(validate(c).ok);
  RobustArsc arsc(c);
  ASSERT_TRUE(arsc.signals().have_gains) << to_string(arsc.signals().last_reason);
  const ArscGains good = arsc.signals().gains;
  // Data of a process with g = 0.01: f(t) = 0.4724 f(t-1) + 0.01 v(t-1).
  double f = 0.0;
  const double v = 1.0;
  for (int i = 0; i < 10; ++i) {
    arsc.step(f, v);
    f = 0.4724 * f + 0.01 * v;
  }
  EXPECT_LT(arsc.model().cutting_gain, 0.05);
  EXPECT_EQ(arsc.signals().last_reason, GuardReason::gain_out_of_range);
  EXPECT_TRUE(arsc.signals().have_gains);
  EXPECT_EQ(arsc.signals().gains.k, good.k);
  EXPECT_EQ(arsc.signals().gains.gamma31, good.gamma31);
}

TEST(ArscGuards, InvalidConfigurationIsRejectedNamingTheField) {
  FaithfulArscConfig c;
  c.rls.forgetting = 1.5;
  EXPECT_STREQ(validate(c).field, "forgetting");
  RobustArscConfig r;
  r.drive.b11 = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(validate(r).ok);
  r = RobustArscConfig{};
  r.estimator.gain_min = 20.0;  // above gain_max
  EXPECT_STREQ(validate(r).field, "gain_min");
}

}  // namespace
}  // namespace tnv::fw::arsc
