// The alpha-beta tracker the robust ARSC designs with on a noisy force
// (gain_trend_filter.hpp): off, it passes the estimate through untouched;
// on, it follows a ramp without lag and averages noise on a constant.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "firmware/adaptive/arsc/gain_trend_filter.hpp"

namespace tnv::fw::arsc {
namespace {

TEST(ArscGainTrend, OffPassesTheEstimateThroughBitForBit) {
  GainTrendFilter off(GainTrendParams{});
  EXPECT_FALSE(off.enabled());
  for (double g : {0.158, 0.3141592653589793, 20.0}) EXPECT_EQ(off.update(g, 1e-3, 10.0), g);
  EXPECT_FALSE(validate(GainTrendParams{0.0}).ok);
  EXPECT_FALSE(validate(GainTrendParams{1.5}).ok);
  EXPECT_TRUE(validate(GainTrendParams{0.4}).ok);
}

TEST(ArscGainTrend, OnARampItPredictsTheNextSampleWithoutLag) {
  GainTrendFilter f(GainTrendParams{0.4});
  double predicted = 0.0;
  for (int k = 0; k < 100; ++k) {
    const double g = 0.158 + 0.0063 * k;  // S3's depth ramp: b21 * 0.8 mm / 100 samples per sample
    predicted = f.update(g, 1e-3, 10.0);
  }
  EXPECT_NEAR(predicted, 0.158 + 0.0063 * 100, 1e-9) << "the gain of the next sample, where the new gains act";
}

TEST(ArscGainTrend, OnAConstantItAveragesTheNoise) {
  GainTrendFilter f(GainTrendParams{0.4});
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 1e-3);
  double sum_sq = 0.0;
  int n = 0;
  for (int k = 0; k < 4000; ++k) {
    const double out = f.update(0.5 + noise(rng), 1e-3, 10.0);
    if (k >= 100) {
      sum_sq += (out - 0.5) * (out - 0.5);
      ++n;
    }
  }
  EXPECT_LT(std::sqrt(sum_sq / n), 0.8e-3) << "rms error of the predicted gain against 1e-3 on its input";
  EXPECT_EQ(f.update(100.0, 1e-3, 10.0), 10.0) << "projected onto [gain_min, gain_max]";
}

}  // namespace
}  // namespace tnv::fw::arsc
