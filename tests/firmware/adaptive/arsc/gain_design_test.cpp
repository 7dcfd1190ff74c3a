// The gain design proves itself: the characteristic polynomial of the
// assembled closed loop equals the requested one (issue 8 item 1).
#include <gtest/gtest.h>

#include <random>

#include "firmware/adaptive/arsc/closed_loop_matrix.hpp"
#include "firmware/adaptive/arsc/faithful_gain_solve.hpp"
#include "firmware/adaptive/arsc/pole_sets.hpp"
#include "firmware/adaptive/arsc/robust_gain_solve.hpp"
#include "tests/firmware/adaptive/arsc/arsc_test_models.hpp"

namespace tnv::fw::arsc {
namespace {

constexpr PoleSet kSets[] = {PoleSet::case1, PoleSet::case2, PoleSet::case3, PoleSet::case4};

void expect_coefficients(const std::array<double, 7>& got, const std::array<double, 7>& want, const char* what) {
  for (std::size_t i = 0; i < 7; ++i)
    EXPECT_NEAR(got[i], want[i], 1e-9 * (1.0 + std::fabs(want[i]))) << what << ": d" << i + 1;
}

TEST(ArscPoleSets, CoefficientsAreThoseOfThePaperPoles) {
  // case1: (z - 0.21)^7 -> d1 = -7 * 0.21, d7 = -0.21^7
  const auto d1 = desired_coefficients(paper_poles(PoleSet::case1));
  EXPECT_NEAR(d1[0], -1.47, 1e-12);
  EXPECT_NEAR(d1[6], -std::pow(0.21, 7), 1e-15);
  // case3: the sum of the poles is 0.19 + 6 * 0.2 cos 68.8 deg
  const auto d3 = desired_coefficients(paper_poles(PoleSet::case3));
  EXPECT_NEAR(d3[0], -(0.19 + 1.2 * std::cos(68.8 * std::numbers::pi / 180.0)), 1e-12);
}

TEST(ArscFaithfulDesign, Fig3IsTheCharacteristicPolynomialOfFig2ForAnyGains) {
  // P K^v - delta = d(K) - d* for every model and every K^v: the corrected
  // Fig. 3 is exactly the affine map from K^v to the coefficients d2..d7.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Arv2Model m = test::random_stable_model(rng);
    FixedGains f{u(rng), u(rng), u(rng), u(rng), u(rng), u(rng)};
    std::array<double, 7> d_star{};
    for (double& d : d_star) d = u(rng);
    const Fig3System sys = fig3_system(m, d_star, f);
    ArscGains g = with_fixed(f);
    g.gamma01 = sys.gamma01;
    g.k = u(rng);
    g.gamma11 = u(rng);
    g.gamma13 = u(rng);
    g.gamma22 = u(rng);
    g.gamma31 = u(rng);
    g.gamma32 = u(rng);
    const Eigen::Matrix<double, 6, 1> kv = (Eigen::Matrix<double, 6, 1>() << g.k, g.gamma11, g.gamma13, g.gamma22,
                                            g.gamma31, g.gamma32).finished();
    const Eigen::Matrix<double, 6, 1> lhs = sys.p * kv - sys.delta;
    const auto d = characteristic_coefficients<7>(closed_loop_matrix(m, g));
    EXPECT_NEAR(d[0], d_star[0], 1e-12) << "eq. (25) must give d1 = d1*";
    for (int i = 0; i < 6; ++i)
      EXPECT_NEAR(lhs(i), d[static_cast<std::size_t>(i) + 1] - d_star[static_cast<std::size_t>(i) + 1], 1e-9)
          << "trial " << trial << ", row d" << i + 2;
  }
}

TEST(ArscFaithfulDesign, SevenBySevenHasTheRequestedCoefficientsForThePoleSetsAndRandomModels) {
  // The paper's starting estimates (eq. 29) for the solvable sets.
  for (PoleSet s : {PoleSet::case1, PoleSet::case3, PoleSet::case4}) {
    const auto want = desired_coefficients(paper_poles(s));
    const GainDesign d = solve_faithful_gains(paper_initial_model(), want, FixedGains{}, GuardLimits{});
    ASSERT_EQ(d.reason, GuardReason::none) << to_string(s);
    expect_coefficients(characteristic_coefficients<7>(closed_loop_matrix(paper_initial_model(), d.gains)), want,
                        to_string(s));
  }
  // Random stable models, all four sets.
  std::mt19937 rng(11);
  int solved = 0;
  for (int trial = 0; trial < 100; ++trial) {
    const Arv2Model m = test::random_stable_model(rng);
    for (PoleSet s : kSets) {
      const auto want = desired_coefficients(paper_poles(s));
      const GainDesign d = solve_faithful_gains(m, want, FixedGains{}, GuardLimits{});
      if (d.reason != GuardReason::none) continue;
      ++solved;
      expect_coefficients(characteristic_coefficients<7>(closed_loop_matrix(m, d.gains)), want, to_string(s));
    }
  }
  EXPECT_GT(solved, 250) << "most random models must be designable";
}

TEST(ArscFaithfulDesign, PlacedPolesAreThePaperPoles) {
  const auto poles = paper_poles(PoleSet::case4);
  const GainDesign d =
      solve_faithful_gains(paper_initial_model(), desired_coefficients(poles), FixedGains{}, GuardLimits{});
  ASSERT_EQ(d.reason, GuardReason::none);
  const Matrix7 a = closed_loop_matrix(paper_initial_model(), d.gains);
  // Every requested pole is a root of det(zI - A) (a triple pair is
  // sensitive, so check the polynomial, not eigenvalue distances).
  for (const auto& z : poles) {
    const Eigen::Matrix<std::complex<double>, 7, 7> m =
        z * Eigen::Matrix<std::complex<double>, 7, 7>::Identity() - a.cast<std::complex<double>>();
    EXPECT_LT(std::abs(m.determinant()), 1e-12) << "pole " << z;
  }
}

// The robust design on an independent realisation: states f, v, u in
// flight, eta, eps1, eps2.
Eigen::Matrix<double, 6, 6> robust_loop_matrix(const StructuredModel& m, const ArscGains& g) {
  const DriveModel& d = m.drive;
  Eigen::Matrix<double, 6, 6> a = Eigen::Matrix<double, 6, 6>::Zero();
  a(0, 0) = -m.a21;
  a(0, 1) = m.cutting_gain;                   // f(t+1) = -a21 f + g v
  a(1, 0) = -d.c11;
  a(1, 1) = -d.a11;
  a(1, 2) = d.b11;                            // v(t+1) = -a11 v + b11 w - c11 f
  a.row(2) << g.gamma31, g.gamma32, 0.0, g.k, g.gamma41, g.gamma42;  // w(t+1) = u(t)
  a.row(3) << 1.0, 0.0, 0.0, 1.0, 0.0, 0.0;
  a.row(4) << g.gamma11, g.gamma12, 0.0, g.gamma21, g.gamma01, g.gamma02;
  a.row(5) << 0.0, g.gamma13, 0.0, g.gamma22, 0.0, g.gamma03;
  return a;
}

TEST(ArscRobustDesign, SixBySixHasTheRequestedCoefficientsForThePoleSetsAndRandomCuttingGains) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> g_dist(0.05, 1.5);
  for (FreeDirection free : {FreeDirection::min_norm, FreeDirection::min_g_sensitivity}) {
    for (PoleSet s : kSets) {
      const auto want = desired_coefficients(six_of_seven(paper_poles(s)));
      for (int trial = 0; trial < 30; ++trial) {
        StructuredModel m;
        m.cutting_gain = g_dist(rng);
        RobustDesignLimits limits;
        limits.free_direction = free;
        const RobustDesign d = solve_robust_gains(m, want, FixedGains{}, limits);
        ASSERT_EQ(d.reason, GuardReason::none) << to_string(s) << " g " << m.cutting_gain;
        const auto got = characteristic_coefficients<6>(robust_loop_matrix(m, d.gains));
        for (std::size_t i = 0; i < 6; ++i)
          EXPECT_NEAR(got[i], want[i], 1e-9 * (1.0 + std::fabs(want[i]))) << to_string(s) << " d" << i + 1;
      }
    }
  }
}

TEST(ArscRobustDesign, MinimumSensitivityChoiceIsNoMoreSensitiveToTheCuttingGainThanMinimumNorm) {
  const auto want = desired_coefficients(six_of_seven(paper_poles(PoleSet::case3)));
  StructuredModel m;
  m.cutting_gain = 0.3;
  const auto sensitivity = [&](FreeDirection free) {
    RobustDesignLimits limits;
    limits.free_direction = free;
    const RobustDesign d = solve_robust_gains(m, want, FixedGains{}, limits);
    StructuredModel moved = m;
    moved.cutting_gain *= 1.01;
    const auto a = robust_closed_loop_coefficients(moved, d.gains);
    double s2 = 0.0;
    for (std::size_t i = 0; i < 6; ++i) s2 += (a[i] - want[i]) * (a[i] - want[i]);
    return std::sqrt(s2);
  };
  EXPECT_LE(sensitivity(FreeDirection::min_g_sensitivity), sensitivity(FreeDirection::min_norm) * (1.0 + 1e-9));
}

}  // namespace
}  // namespace tnv::fw::arsc
