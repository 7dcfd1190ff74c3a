#include "tools/campaign/sampling.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace tnv::campaign {
namespace {

TEST(CampaignSampling, InverseNormalCdfMatchesKnownQuantiles) {
  EXPECT_NEAR(inverse_normal_cdf(0.5), 0.0, 1e-15);
  EXPECT_NEAR(inverse_normal_cdf(0.975), 1.959963984540054, 1e-13);
  EXPECT_NEAR(inverse_normal_cdf(0.841344746068543), 1.0, 1e-12);
  EXPECT_NEAR(inverse_normal_cdf(1e-6), -4.753424308822899, 1e-10);
  EXPECT_NEAR(inverse_normal_cdf(1.0 - 1e-6), 4.753424308822899, 1e-8);
}

TEST(CampaignSampling, TheSameSeedGivesTheSamePointsAndAnotherSeedOthers) {
  const auto a = unit_samples(50, 3, 7, Sampling::random);
  EXPECT_EQ(a, unit_samples(50, 3, 7, Sampling::random));
  EXPECT_NE(a, unit_samples(50, 3, 8, Sampling::random));
  for (double v : a) {
    EXPECT_GT(v, 0.0);
    EXPECT_LT(v, 1.0);
  }
}

TEST(CampaignSampling, LatinHypercubePutsOnePointInEachStratumOfEachDimension) {
  constexpr std::size_t kRuns = 37, kDims = 4;
  const auto u = unit_samples(kRuns, kDims, 11, Sampling::latin_hypercube);
  for (std::size_t d = 0; d < kDims; ++d) {
    std::set<std::size_t> strata;
    for (std::size_t r = 0; r < kRuns; ++r) strata.insert(static_cast<std::size_t>(u[r * kDims + d] * kRuns));
    EXPECT_EQ(strata.size(), kRuns) << "dimension " << d;
  }
  // Random sampling of the same size does not (with overwhelming probability).
  const auto v = unit_samples(kRuns, 1, 11, Sampling::random);
  std::set<std::size_t> strata;
  for (double x : v) strata.insert(static_cast<std::size_t>(x * kRuns));
  EXPECT_LT(strata.size(), kRuns);
}

}  // namespace
}  // namespace tnv::campaign
