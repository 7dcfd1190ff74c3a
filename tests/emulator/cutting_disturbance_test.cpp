#include "emulator/cutting_disturbance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "emulator/substep_timing.hpp"

namespace tnv::emu {
namespace {

constexpr double kPi = std::numbers::pi;

// The reference-plant formula written out independently of the emulator.
struct DirectCutting {
  CuttingParams cut;
  CircleParams circle;
  double start_s;  // motion start = servo-on + dwell

  double duration_s() const { return 2 * kPi * circle.radius_mm / circle.feed_mm_s + circle.ramp_s; }
  // Commanded feed speed and arc at time t since the start.
  void path(double t, double& speed, double& arc) const {
    const double F = circle.feed_mm_s, r = circle.ramp_s, T = duration_s(), L = 2 * kPi * circle.radius_mm;
    if (t < 0) {
      speed = 0, arc = 0;
    } else if (t < r) {
      speed = F / 2 * (1 - std::cos(kPi * t / r)), arc = F / 2 * (t - r / kPi * std::sin(kPi * t / r));
    } else if (t < T - r) {
      speed = F, arc = F * r / 2 + F * (t - r);
    } else if (t < T) {
      const double te = T - t;
      speed = F / 2 * (1 - std::cos(kPi * te / r)), arc = L - F / 2 * (te - r / kPi * std::sin(kPi * te / r));
    } else {
      speed = 0, arc = L;
    }
  }
  CuttingVector at(double t) const {
    double speed = 0, arc = 0;
    path(t - start_s, speed, arc);
    const double theta = arc / circle.radius_mm;
    const double level = speed / circle.feed_mm_s * std::pow(900.0 / cut.spindle_rpm, cut.exponent) *
                         (cut.mean_mm_s + cut.amplitude_mm_s *
                                              std::sin(2 * kPi * cut.flutes * cut.spindle_rpm / 60.0 * t + cut.phase_rad));
    const double tx = -std::sin(theta), ty = std::cos(theta);  // feed direction
    const double nx = std::cos(theta), ny = std::sin(theta);   // outward normal
    return {level * (-tx + nx) / std::sqrt(2.0), level * (-ty + ny) / std::sqrt(2.0)};
  }
};

CuttingParams cutting_at(double rpm) {
  CuttingParams p;
  p.enabled = true;
  p.spindle_rpm = rpm;
  p.phase_rad = 0.3;
  return p;
}

TEST(CuttingDisturbance, DisabledIsZero) {
  CuttingDisturbance cutting(CuttingParams{}, CircleParams{});
  cutting.servo_on_at(0.0);
  const CuttingVector d = cutting.at_substep(100'000);  // 1 s: mid-circle
  EXPECT_EQ(d.x_mm_s, 0.0);
  EXPECT_EQ(d.y_mm_s, 0.0);
}

TEST(CuttingDisturbance, ZeroBeforeServoOnBeforeStartAndAfterEnd) {
  const CircleParams circle{};
  CuttingDisturbance cutting(cutting_at(900), circle);
  EXPECT_EQ(cutting.at_substep(1'000).magnitude_mm_s(), 0.0) << "no servo-on yet";
  cutting.servo_on_at(0.02);
  const auto start = static_cast<std::uint64_t>((0.02 + circle.dwell_s) * 1e5);
  for (std::uint64_t k = 2'000; k <= start; ++k) {
    ASSERT_EQ(cutting.at_substep(k).magnitude_mm_s(), 0.0) << "cutting during the dwell at t = " << substep_time_s(k);
  }
  EXPECT_GT(cutting.at_substep(start + 10).magnitude_mm_s(), 0.0);
  const DirectCutting direct{cutting_at(900), circle, 0.02 + circle.dwell_s};
  const auto end = static_cast<std::uint64_t>(std::ceil((direct.start_s + direct.duration_s()) * 1e5));
  for (std::uint64_t k = end; k < end + 1'000; ++k) {
    ASSERT_EQ(cutting.at_substep(k).magnitude_mm_s(), 0.0) << "cutting after the end at t = " << substep_time_s(k);
  }
}

class CuttingPerSpindle : public ::testing::TestWithParam<double> {};

TEST_P(CuttingPerSpindle, EqualsTheDirectFormulaAtEverySubstep) {
  const double rpm = GetParam();
  const CircleParams circle{};
  CuttingDisturbance cutting(cutting_at(rpm), circle);
  const double servo_on_s = 0.01;
  cutting.servo_on_at(servo_on_s);
  const DirectCutting direct{cutting_at(rpm), circle, servo_on_s + circle.dwell_s};
  const auto last = static_cast<std::uint64_t>((direct.start_s + direct.duration_s()) * 1e5) + 100;
  double worst = 0.0;
  double x[100], y[100];
  for (std::uint64_t first = 0; first < last; first += 100) {
    cutting.fill(first, 100, x, y);
    for (std::uint64_t i = 0; i < 100; ++i) {
      const CuttingVector e = direct.at(substep_time_s(first + i));
      worst = std::max({worst, std::abs(x[i] - e.x_mm_s), std::abs(y[i] - e.y_mm_s)});
    }
  }
  EXPECT_LT(worst, 1e-11) << "largest difference from the reference-plant formula, mm/s";
}

TEST_P(CuttingPerSpindle, PulsesAtToothPassingFrequencyWithKienzleScaling) {
  const double rpm = GetParam();
  CuttingParams params = cutting_at(rpm);
  CuttingDisturbance cutting(params, CircleParams{});
  cutting.servo_on_at(0.0);
  // One second of cruise, magnitude only (direction turns slowly).
  const std::uint64_t first = 200'000, n = 100'000;
  std::complex<double> at_tooth{}, mean{};
  auto component = [&](double f_hz, std::uint64_t k, double value) {
    return value * std::polar(1.0, -2 * kPi * f_hz * substep_time_s(k));
  };
  const double tooth_hz = 2 * rpm / 60.0;
  std::complex<double> off_tooth{};
  double x[100], y[100];
  for (std::uint64_t k = first; k < first + n; ++k) {
    if ((k - first) % 100 == 0) cutting.fill(k, 100, x, y);
    const double m = std::hypot(x[(k - first) % 100], y[(k - first) % 100]);
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

TEST(CuttingDisturbance, OpposesFeedRotated45DegreesOutward) {
  const CircleParams circle{};
  CuttingDisturbance cutting(cutting_at(1200), circle);
  cutting.servo_on_at(0.0);
  for (std::uint64_t k = 100'000; k < 1'900'000; k += 123'457) {
    const CuttingVector d = cutting.at_substep(k);
    const CirclePathPoint& p = cutting.path().circle().at(substep_time_s(k) - circle.dwell_s);
    const double m = d.magnitude_mm_s();
    ASSERT_GT(m, 0.0);
    const double along_feed = (d.x_mm_s * -p.sin_angle + d.y_mm_s * p.cos_angle) / m;
    const double outward = (d.x_mm_s * p.cos_angle + d.y_mm_s * p.sin_angle) / m;
    EXPECT_NEAR(along_feed, -std::sqrt(0.5), 1e-12) << "cos of angle to the feed direction";
    EXPECT_NEAR(outward, std::sqrt(0.5), 1e-12) << "cos of angle to the outward normal";
  }
}

}  // namespace
}  // namespace tnv::emu
