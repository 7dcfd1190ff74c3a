#include "emulator/commanded_circle.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "emulator/circle_path_stepper.hpp"
#include "emulator/substep_timing.hpp"

namespace tnv::emu {
namespace {

const CircleParams kS1{};  // R 6 mm, F 2 mm/s, ramps 0.1 s, dwell 0.5 s

TEST(CommandedCircle, DurationAndArcLength) {
  const CommandedCircle circle(kS1);
  EXPECT_NEAR(circle.arc_length_mm(), 2.0 * std::numbers::pi * 6.0, 1e-12);
  EXPECT_NEAR(circle.duration_s(), 2.0 * std::numbers::pi * 6.0 / 2.0 + 0.1, 1e-12);
}

TEST(CommandedCircle, FullRevolutionCounterClockwiseFromRZero) {
  const CommandedCircle circle(kS1);
  const CirclePathPoint start = circle.at(0.0);
  EXPECT_EQ(start.arc_mm, 0.0);
  EXPECT_EQ(start.cos_angle, 1.0);
  const CirclePathPoint quarter = circle.at(0.05 + 0.25 * circle.arc_length_mm() / 2.0);
  EXPECT_NEAR(quarter.arc_mm, 0.25 * circle.arc_length_mm(), 1e-12);
  EXPECT_NEAR(quarter.sin_angle, 1.0, 1e-12) << "a quarter of the way the tool is at (0, R)";
  const CirclePathPoint end = circle.at(circle.duration_s());
  EXPECT_NEAR(end.arc_mm, circle.arc_length_mm(), 1e-12) << "arc at the end, mm";
  EXPECT_EQ(end.speed_mm_s, 0.0);
  EXPECT_NEAR(circle.at(circle.duration_s() - 1e-9).arc_mm, circle.arc_length_mm(), 1e-12);
  EXPECT_EQ(circle.at(-1e-9).speed_mm_s, 0.0);
  EXPECT_EQ(circle.at(circle.duration_s() + 1.0).speed_mm_s, 0.0);
}

TEST(CommandedCircle, RaisedCosineSpeedProfile) {
  const CommandedCircle circle(kS1);
  EXPECT_NEAR(circle.at(0.05).speed_mm_s, 1.0, 1e-12) << "half feed at mid start-ramp";
  EXPECT_NEAR(circle.at(0.05).arc_mm, 0.5 * 2.0 * (0.05 - 0.1 / std::numbers::pi), 1e-12);
  EXPECT_NEAR(circle.at(0.1).arc_mm, 2.0 * 0.1 / 2.0, 1e-12) << "start ramp covers F ramp / 2";
  EXPECT_EQ(circle.at(5.0).speed_mm_s, 2.0);
  EXPECT_NEAR(circle.at(circle.duration_s() - 0.05).speed_mm_s, 1.0, 1e-12);
}

TEST(CommandedCircle, SpeedIsContinuousAndIsTheArcDerivative) {
  const CommandedCircle circle(kS1);
  const double dt = 1e-5;
  double max_jump = 0.0, max_mismatch = 0.0;
  CirclePathPoint previous = circle.at(-dt);
  for (double t = 0.0; t < circle.duration_s() + 2 * dt; t += dt) {
    const CirclePathPoint p = circle.at(t);
    max_jump = std::max(max_jump, std::abs(p.speed_mm_s - previous.speed_mm_s));
    const double mean_speed = 0.5 * (p.speed_mm_s + previous.speed_mm_s);
    max_mismatch = std::max(max_mismatch, std::abs((p.arc_mm - previous.arc_mm) / dt - mean_speed));
    previous = p;
  }
  // Largest raised-cosine slope: F pi / (2 ramp) = 31.4 mm/s^2 -> 3.1e-4 mm/s per 10 us.
  EXPECT_LT(max_jump, 3.2e-4) << "speed step between samples 10 us apart, mm/s";
  EXPECT_LT(max_mismatch, 1e-6) << "arc increments vs speed, mm/s";
}

class CirclePathStepperRuns : public ::testing::TestWithParam<std::size_t> {};

TEST_P(CirclePathStepperRuns, FillMatchesTheClosedFormAtEverySubstep) {
  const std::size_t chunk = GetParam();
  CirclePathStepper stepper(kS1);
  const CommandedCircle& circle = stepper.circle();
  const std::uint64_t servo_on = 1'234;
  stepper.servo_on_at(substep_time_s(servo_on));
  const double start_s = substep_time_s(servo_on) + kS1.dwell_s;
  const auto last = static_cast<std::uint64_t>((start_s + circle.duration_s()) * 1e5) + 200;
  double worst_speed = 0.0, worst_direction = 0.0;
  double speed[100], cos_angle[100], sin_angle[100];
  for (std::uint64_t first = 0; first < last; first += chunk) {
    stepper.fill(first, chunk, speed, cos_angle, sin_angle);
    for (std::size_t i = 0; i < chunk; ++i) {
      const CirclePathPoint exact = circle.at(substep_time_s(first + i) - start_s);
      worst_speed = std::max(worst_speed, std::abs(speed[i] - exact.speed_mm_s));
      worst_direction = std::max({worst_direction, std::abs(cos_angle[i] - exact.cos_angle),
                                  std::abs(sin_angle[i] - exact.sin_angle)});
    }
  }
  EXPECT_LT(worst_speed, 1e-12) << "mm/s";
  EXPECT_LT(worst_direction, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(ChunkSizes, CirclePathStepperRuns, ::testing::Values(100, 37, 1));

TEST(CirclePathStepper, RestsAtStartUntilServoOn) {
  CirclePathStepper stepper(kS1);
  double speed[3], cos_angle[3], sin_angle[3];
  stepper.fill(10, 3, speed, cos_angle, sin_angle);
  EXPECT_EQ(speed[2], 0.0);
  EXPECT_EQ(cos_angle[2], 1.0);
  EXPECT_EQ(stepper.at_substep(10).speed_mm_s, 0.0);
  EXPECT_EQ(stepper.at_substep(10).cos_angle, 1.0);
  EXPECT_FALSE(stepper.motion_scheduled());
}

}  // namespace
}  // namespace tnv::emu
