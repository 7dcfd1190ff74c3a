// The cutting model on its own: d_cut for a given table velocity.
#include "emulator/cutting_disturbance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "emulator/substep_timing.hpp"
#include "tests/emulator/cutting_reference.hpp"

namespace tnv::emu {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kFeedMmS = 2.0;  // F of the built-in scenarios

TEST(CuttingDisturbance, DisabledIsZero) {
  CuttingDisturbance cutting(CuttingParams{}, kFeedMmS);
  EXPECT_FALSE(cutting.enabled());
  const CuttingVector d = cutting.at_substep(100'000, 2.0, -1.0);
  EXPECT_EQ(d.x_mm_s, 0.0);
  EXPECT_EQ(d.y_mm_s, 0.0);
}

TEST(CuttingDisturbance, ZeroAtRest) {
  const CuttingDisturbance cutting(test_support::cutting_at(900), kFeedMmS);
  for (std::uint64_t k = 0; k < 200'000; k += 1'237) {
    ASSERT_EQ(cutting.at_substep(k, 0.0, 0.0).magnitude_mm_s(), 0.0) << "table at rest, t = " << substep_time_s(k);
  }
}

class CuttingPerSpindle : public ::testing::TestWithParam<double> {};

// Any velocity, every sub-step of fills of 100: the reference-plant formula
// written with |v|, the unit travel direction and its right-hand normal.
TEST_P(CuttingPerSpindle, EqualsTheDirectFormulaForAnyVelocity) {
  const CuttingParams params = test_support::cutting_at(GetParam());
  const CuttingDisturbance cutting(params, kFeedMmS);
  double worst_mm_s = 0.0;
  double load[CuttingDisturbance::kMaxFill];
  for (std::uint64_t first = 0; first < 300'000; first += 100) {
    cutting.fill_load_per_speed(first, 100, load);
    for (std::uint64_t i = 0; i < 100; ++i) {
      const double t_s = substep_time_s(first + i);
      // A velocity that turns through every direction and changes its speed.
      const double vx = 3.0 * std::cos(1.3 * t_s) + 0.5, vy = 2.0 * std::sin(2.1 * t_s);
      const CuttingVector d = CuttingDisturbance::force(load[i], vx, vy);
      const CuttingVector e = test_support::direct_cutting(params, kFeedMmS, t_s, vx, vy);
      worst_mm_s = std::max({worst_mm_s, std::abs(d.x_mm_s - e.x_mm_s), std::abs(d.y_mm_s - e.y_mm_s)});
    }
  }
  EXPECT_LT(worst_mm_s, 1e-11) << "largest difference from the reference-plant formula, mm/s";
}

TEST_P(CuttingPerSpindle, PulsesAtToothPassingFrequencyWithKienzleScaling) {
  const double rpm = GetParam();
  const CuttingDisturbance cutting(test_support::cutting_at(rpm), kFeedMmS);
  // One second at the programmed feed along +X.
  const std::uint64_t first = 200'000, n = 100'000;
  std::complex<double> at_tooth{}, off_tooth{}, mean{};
  auto component = [&](double f_hz, std::uint64_t k, double value) {
    return value * std::polar(1.0, -2 * kPi * f_hz * substep_time_s(k));
  };
  const double tooth_hz = 2 * rpm / 60.0;
  double load[CuttingDisturbance::kMaxFill];
  for (std::uint64_t k = first; k < first + n; ++k) {
    if ((k - first) % 100 == 0) cutting.fill_load_per_speed(k, 100, load);
    const double m = CuttingDisturbance::force(load[(k - first) % 100], kFeedMmS, 0.0).magnitude_mm_s();
    at_tooth += component(tooth_hz, k, m);
    off_tooth += component(tooth_hz + 7.0, k, m);
    mean += m;
  }
  const double scale = std::pow(900.0 / rpm, 0.75);
  EXPECT_NEAR(std::abs(mean) / n, scale * 0.6, 1e-6) << "mean cutting level, mm/s";
  EXPECT_NEAR(2.0 * std::abs(at_tooth) / n, scale * 0.6, 1e-6) << "amplitude at " << tooth_hz << " Hz, mm/s";
  EXPECT_LT(2.0 * std::abs(off_tooth) / n, 1e-6) << "amplitude 7 Hz off the tooth frequency, mm/s";
}

INSTANTIATE_TEST_SUITE_P(S1Spindles, CuttingPerSpindle, ::testing::Values(900.0, 1200.0, 1500.0));

TEST(CuttingDisturbance, OpposesTravelRotated45DegreesToItsRightInEveryDirection) {
  const CuttingDisturbance cutting(test_support::cutting_at(1200), kFeedMmS);
  for (int deg = -180; deg < 180; deg += 15) {
    const double a = deg * kPi / 180.0;
    const double vx = 2.0 * std::cos(a), vy = 2.0 * std::sin(a);
    const CuttingVector d = cutting.at_substep(123'457, vx, vy);
    ASSERT_GT(d.magnitude_mm_s(), 0.0);
    EXPECT_NEAR(test_support::angle_from_velocity_deg(d, vx, vy), -135.0, 1e-9) << "deg, travelling at " << deg << " deg";
  }
}

TEST(CuttingDisturbance, ScalesLinearlyWithSpeed) {
  const CuttingDisturbance cutting(test_support::cutting_at(1500), kFeedMmS);
  for (std::uint64_t k = 0; k < 100'000; k += 7'919) {
    const CuttingVector at_feed = cutting.at_substep(k, 1.2, -1.6);  // 2 mm/s
    for (const double times : {0.25, 3.0, 10.0}) {
      const CuttingVector d = cutting.at_substep(k, 1.2 * times, -1.6 * times);
      EXPECT_NEAR(d.x_mm_s, times * at_feed.x_mm_s, 1e-14 * times) << times << " x the speed, mm/s";
      EXPECT_NEAR(d.y_mm_s, times * at_feed.y_mm_s, 1e-14 * times) << times << " x the speed, mm/s";
    }
  }
}

// Fed the commanded S1 circle's velocity, the table-following model is the
// reference plant's circle model (the model the emulator used before it
// followed the table) to rounding.
TEST(CuttingDisturbance, OnTheCommandedS1CircleItIsTheCircleModel) {
  const CircleParams circle{};
  const double start_s = 0.01 + circle.dwell_s;
  for (const double rpm : {900.0, 1200.0, 1500.0}) {
    const CuttingParams params = test_support::cutting_at(rpm);
    const CuttingDisturbance cutting(params, circle.feed_mm_s);
    const test_support::S1Circle path{circle, start_s};
    double worst_mm_s = 0.0;
    const auto last = static_cast<std::uint64_t>((start_s + path.duration_s()) * 1e5) + 100;
    for (std::uint64_t k = 0; k < last; k += 7) {
      const double t_s = substep_time_s(k);
      const test_support::PathSample p = path.at(t_s);
      const CuttingVector d = cutting.at_substep(k, p.vx_mm_s, p.vy_mm_s);
      const CuttingVector e = test_support::circle_model_cutting(params, circle, start_s, t_s);
      worst_mm_s = std::max({worst_mm_s, std::abs(d.x_mm_s - e.x_mm_s), std::abs(d.y_mm_s - e.y_mm_s)});
    }
    EXPECT_LT(worst_mm_s, 1e-12) << "mm/s at " << rpm << " rpm";
  }
}

}  // namespace
}  // namespace tnv::emu
