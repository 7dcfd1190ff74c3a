// S4 eqs. (4)-(8): the RLS on the log deflection model.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>

#include "firmware/adaptive/boring/log_model_rls.hpp"

namespace tnv::fw {
namespace {

const BoringTheta kTrue(std::log(0.0871), 0.5025, 0.2676);  // Table 1

struct Sample {
  BoringRegressor x;
  double y;
};

// Noiseless data over the paper's range: S 0.01..0.5 mm/rev, L 40..310 mm.
std::vector<Sample> noiseless(int n, BoringLogBase base, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ls(std::log(0.01), std::log(0.5));
  std::uniform_real_distribution<double> ll(std::log(40.0), std::log(310.0));
  std::vector<Sample> out;
  const double k = ln_of_base(base);
  const BoringTheta theta(kTrue(0) / k, kTrue(1), kTrue(2));
  for (int i = 0; i < n; ++i) {
    const double s = std::exp(ls(rng));
    const double l = std::exp(ll(rng));
    const BoringRegressor x = boring_regressor(s, l, base);
    out.push_back({x, model_log(0.0871 * std::pow(s, 0.5025) * std::pow(l, 0.2676), base)});
    EXPECT_NEAR(out.back().y, x.dot(theta), 1e-12) << "eq. (4) with v = 0";
  }
  return out;
}

TEST(LogModelRls, EqualsTheBatchRegularisedLeastSquaresSolution) {
  // With P0 = p0 I and denominators (s, s) the recursion is exactly
  // theta_N = (I/p0 + X'X/s)^-1 (theta0/p0 + X'y/s): checks (5), (6).
  const auto data = noiseless(40, BoringLogBase::natural, 3);
  const BoringTheta theta0(-2.0, 1.0, 0.1);
  for (double s : {1.0, 0.0184}) {
    LogModelRls rls;
    rls.reset(theta0, 1.0);
    Eigen::Matrix3d a = Eigen::Matrix3d::Identity();
    Eigen::Vector3d b = theta0;
    for (const Sample& d : data) {
      ASSERT_TRUE(rls.update(d.x, d.y, s, s));
      a += d.x * d.x.transpose() / s;
      b += d.x * d.y / s;
    }
    const BoringTheta batch = a.ldlt().solve(b);
    EXPECT_LT((rls.theta() - batch).cwiseAbs().maxCoeff(), 1e-9) << "s = " << s;
    EXPECT_LT((rls.covariance() - a.inverse()).cwiseAbs().maxCoeff(), 1e-9) << "P = (I + X'X/s)^-1";
  }
}

TEST(LogModelRls, RecoversLogCAlphaBetaOnNoiselessData) {
  const BoringTheta theta0(std::log(0.2), 1.0, 0.0);  // far off: alpha0 = 1, beta0 = 0
  struct Case {
    const char* name;
    double s5, s6;
    int updates;
    double tolerance;
  };
  // With noiseless data the error left is the prior's pull,
  // (I + X'X/s)^-1 (theta0 - theta): it decays as s/N. normalised: the prior
  // I weighs like one measurement (s = 1); kalman/printed with
  // Sigma = (0.005/0.1165)^2 it weighs 1/Sigma = 543 times less.
  const double sigma = std::pow(0.005 / 0.1165, 2);
  for (const Case& c : {Case{"normalised", 1.0, 1.0, 100'000, 1e-3}, Case{"kalman", sigma, sigma, 5000, 1e-4},
                        Case{"printed", sigma, 1.0, 5000, 1e-4}}) {
    for (BoringLogBase base : {BoringLogBase::natural, BoringLogBase::decimal}) {
      LogModelRls rls;
      rls.reset(theta0, 1.0);
      const auto data = noiseless(c.updates, base, 7);
      double error_at_tenth = 0.0;
      const double k = ln_of_base(base);
      const auto error = [&] {
        return std::max({std::fabs(rls.theta()(0) * k - kTrue(0)), std::fabs(rls.theta()(1) - kTrue(1)),
                         std::fabs(rls.theta()(2) - kTrue(2))});
      };
      for (std::size_t i = 0; i < data.size(); ++i) {
        ASSERT_TRUE(rls.update(data[i].x, data[i].y, c.s5, c.s6));
        if (i + 1 == data.size() / 10) error_at_tenth = error();
      }
      EXPECT_NEAR(rls.theta()(0) * k, kTrue(0), c.tolerance) << c.name << ": log C (natural)";
      EXPECT_NEAR(rls.theta()(1), kTrue(1), c.tolerance) << c.name << ": alpha";
      EXPECT_NEAR(rls.theta()(2), kTrue(2), c.tolerance) << c.name << ": beta";
      EXPECT_LT(error(), std::max(0.2 * error_at_tenth, 1e-12)) << c.name << ": ten times the data, five times closer";
    }
  }
}

TEST(LogModelRls, CovarianceStaysSymmetricPositiveDefiniteOverManyUpdates) {
  LogModelRls rls;
  rls.reset(BoringTheta::Zero(), 1.0);
  for (const Sample& d : noiseless(20000, BoringLogBase::natural, 11)) ASSERT_TRUE(rls.update(d.x, d.y, 1.0, 1.0));
  const BoringCovariance& p = rls.covariance();
  EXPECT_LT((p - p.transpose()).cwiseAbs().maxCoeff(), 1e-18);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(p);
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
}

TEST(LogModelRls, ResetCovarianceKeepsTheEstimate) {
  LogModelRls rls;
  rls.reset(BoringTheta(1.0, 2.0, 3.0), 1.0);
  const auto data = noiseless(10, BoringLogBase::natural, 5);
  for (const Sample& d : data) rls.update(d.x, d.y, 1.0, 1.0);
  const BoringTheta before = rls.theta();
  rls.reset_covariance(1.0);
  EXPECT_EQ(rls.theta(), before);
  EXPECT_EQ(rls.covariance(), BoringCovariance::Identity());
}

TEST(LogModelRls, RefusesNonFiniteInputsAndChangesNothing) {
  LogModelRls rls;
  rls.reset(BoringTheta(1.0, 0.5, 0.3), 1.0);
  const BoringTheta theta = rls.theta();
  const BoringCovariance p = rls.covariance();
  const BoringRegressor x(1.0, std::log(0.1), std::log(100.0));
  EXPECT_FALSE(rls.update(x, std::nan(""), 1.0, 1.0));
  EXPECT_FALSE(rls.update(BoringRegressor(1.0, INFINITY, 1.0), 0.0, 1.0, 1.0));
  EXPECT_FALSE(rls.update(x, 0.0, 0.0, 1.0)) << "s5 must be > 0";
  EXPECT_FALSE(rls.update(x, 0.0, 1.0, -1.0)) << "s6 must be > 0";
  EXPECT_EQ(rls.theta(), theta);
  EXPECT_EQ(rls.covariance(), p);
}

}  // namespace
}  // namespace tnv::fw
