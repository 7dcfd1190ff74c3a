#include "firmware/timing/m_method_speed.hpp"

#include <gtest/gtest.h>

#include <random>

#include "firmware/timing/encoder_position.hpp"
#include "tests/firmware/test_units.hpp"

namespace tnv::fw {
namespace {

using test_units::kCountMm;

TEST(MMethodSpeed, UsesTheMeasuredPeriodNotANominalOne) {
  // 48 counts in 1.2 ms is 16.667 mm/s; assuming 1 ms would say 20 mm/s.
  EXPECT_NEAR(m_method_speed_mm_s(48, kCountMm, 12'000), 48 * kCountMm / 1.2e-3, 1e-12);
  EXPECT_NEAR(m_method_speed_mm_s(-24, kCountMm, 10'000), -10.0, 1e-12);
  EXPECT_EQ(m_method_speed_mm_s(5, kCountMm, 0), 0.0);
}

TEST(MMethodSpeed, JitteredTickPeriodStillGivesTheTrueSpeedOnAverage) {
  // A table at a constant 2 mm/s, ticks jittered by up to +-20% of a period.
  const double speed_mm_s = 2.0;
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> jitter(-2000, 2000);
  std::uint64_t clock = 0;
  std::int64_t last_count = 0;
  double worst_error = 0.0, sum_speed = 0.0;
  const int n = 5000;
  for (int k = 1; k <= n; ++k) {
    const std::uint32_t period = static_cast<std::uint32_t>(10'000 + jitter(rng));
    clock += period;
    const double position_mm = speed_mm_s * static_cast<double>(clock) / 1e7;
    const std::int64_t count = static_cast<std::int64_t>(std::floor(position_mm / kCountMm));
    const double v = m_method_speed_mm_s(count - last_count, kCountMm, period);
    last_count = count;
    sum_speed += v;
    // One count of quantisation over the measured period is the only error.
    const double bound = kCountMm / (period / 1e7) + 1e-9;
    worst_error = std::max(worst_error, std::fabs(v - speed_mm_s) - bound);
  }
  EXPECT_LE(worst_error, 0.0) << "speed error beyond one count per measured period";
  EXPECT_NEAR(sum_speed / n, speed_mm_s, 0.01) << "mean speed over jittered ticks, mm/s";
}

TEST(ElapsedClocks, TheThirtyTwoBitWrapIsInvisible) {
  EXPECT_EQ(elapsed_clocks(0xFFFFF000u, 0x00001710u), 0x2710u);  // 10,000 clocks across the wrap
}

TEST(EncoderPosition, ExtendsA16BitCounterAcrossTheWrapBothWays) {
  EncoderPosition enc(16);
  enc.reset(65530);
  EXPECT_EQ(enc.update(4), 10);  // 65530 -> 65536+4
  EXPECT_EQ(enc.counts(), 10);
  EXPECT_EQ(enc.update(65520), -20);  // back below zero
  EXPECT_EQ(enc.counts(), -10);
  for (int i = 0; i < 100; ++i) enc.update(static_cast<std::uint32_t>((65520 + 1000 * (i + 1)) & 0xFFFF));
  EXPECT_EQ(enc.counts(), -10 + 100'000) << "100 forward steps of 1000 counts";
}

TEST(EncoderPosition, WorksWithA32BitCounter) {
  EncoderPosition enc(32);
  enc.reset(0xFFFFFFF0u);
  EXPECT_EQ(enc.update(0x10u), 0x20);
}

}  // namespace
}  // namespace tnv::fw
