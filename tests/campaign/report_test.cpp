#include "tools/campaign/report.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tnv::campaign {
namespace {

TEST(CampaignReport, SpearmanOfMonotoneAndReversedAndTiedData) {
  EXPECT_DOUBLE_EQ(spearman({1, 2, 3, 4}, {10, 40, 90, 160}), 1.0);
  EXPECT_DOUBLE_EQ(spearman({1, 2, 3, 4}, {4, 3, 2, 1}), -1.0);
  // Ties get average ranks: x ranks 1.5 1.5 3 4, y ranks 1 2 3 4 -> rho = 0.9487 (scipy.stats.spearmanr).
  EXPECT_NEAR(spearman({1, 1, 2, 3}, {1, 2, 3, 4}), 0.9486832980505138, 1e-12);
  EXPECT_TRUE(std::isnan(spearman({1, 1, 1}, {1, 2, 3})));
}

TEST(CampaignReport, QuantilesInterpolateAsNumpy) {
  const std::vector<double> v = {1, 2, 3, 4, 5};
  EXPECT_DOUBLE_EQ(quantile_sorted(v, 0.5), 3.0);
  EXPECT_DOUBLE_EQ(quantile_sorted(v, 0.9), 4.6);
  EXPECT_DOUBLE_EQ(quantile_sorted(v, 1.0), 5.0);
  EXPECT_TRUE(std::isnan(quantile_sorted({}, 0.5)));
}

}  // namespace
}  // namespace tnv::campaign
