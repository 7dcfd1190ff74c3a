// tools/score/path_score.hpp on samples with known answers: a reference that
// runs a line at constant acceleration, a measured position offset from it.
#include <gtest/gtest.h>

#include <cmath>

#include "tools/score/path_score.hpp"

namespace tnv::hil {
namespace {

using fw::motion::PlanePoint;

gcode::GcodeProgram line_program() {
  gcode::GcodeOptions o;
  const gcode::GcodeResult r = gcode::parse_gcode("G1 X10 F600\n", o);  // 10 mm at 10 mm/s
  EXPECT_FALSE(r.error);
  return r.program;
}

// Rest, then x = a t^2 / 2 up to 10 mm, then rest; y measured `offset_mm` off the line.
std::vector<PathSample> accelerating_run(double accel_mm_s2, double offset_mm, int rest_ticks) {
  std::vector<PathSample> out;
  for (int k = 0; k < rest_ticks; ++k) out.push_back({{0.0, offset_mm}, {0.0, 0.0}});
  for (int k = 1;; ++k) {
    const double t = k * 1e-3;
    const double x = std::min(0.5 * accel_mm_s2 * t * t, 10.0);
    out.push_back({{x, offset_mm}, {x, 0.0}});
    if (x >= 10.0) break;
  }
  for (int k = 0; k < rest_ticks; ++k) out.push_back({{10.0, offset_mm}, {10.0, 0.0}});
  return out;
}

TEST(PathScore, ContourErrorIsTheDistanceToTheProgrammedPathOverTheMotionWindow) {
  const gcode::GcodeProgram p = line_program();
  fw::motion::MotionLimits limits;  // 500 mm/s^2 per axis
  const std::vector<PathSample> run = accelerating_run(100.0, 0.002, 50);
  const PathScore s = score_path(p, run, limits);
  EXPECT_NEAR(s.contour_error_max_um, 2.0, 1e-9);
  EXPECT_NEAR(s.contour_error_mean_um, 2.0, 1e-9);
  EXPECT_NEAR(s.contour_error_std_um, 0.0, 1e-9);
  EXPECT_NEAR(s.path_deviation_max_um, 0.0, 1e-9);
  // x reaches 10 mm after sqrt(2 * 10 / 100) = 0.4472 s: 448 ticks, the window one more than the moving ones.
  EXPECT_NEAR(s.cycle_time_s, 0.448, 1e-9);
  EXPECT_EQ(s.window_samples, 449u);
  EXPECT_NEAR(s.feed_ratio, 1.0 / 0.448, 1e-9) << "programmed 1 s (10 mm at 10 mm/s) over the cycle";
  // 100 mm/s^2 of 500, and the jump to rest at the end (the last step is shorter than a*dt).
  EXPECT_GE(s.accel_ratio_max, 0.2 - 1e-6);
}

TEST(PathScore, AccelerationAndJerkAreFiniteDifferencesOverTheAxisLimits) {
  const gcode::GcodeProgram p = line_program();
  fw::motion::MotionLimits limits;
  limits.axis[0].accel_mm_s2 = 200.0;
  limits.axis[0].jerk_mm_s3 = 1e5;
  std::vector<PathSample> run;
  // A constant-acceleration stretch of 100 mm/s^2 that starts with one jerk of 100 / 1 ms.
  for (int k = 0; k < 10; ++k) run.push_back({{0.0, 0.0}, {0.0, 0.0}});
  for (int k = 1; k <= 200; ++k) {
    const double t = k * 1e-3;
    run.push_back({{0.5 * 100.0 * t * t, 0.0}, {0.5 * 100.0 * t * t, 0.0}});
  }
  const PathScore s = score_path(p, run, limits);
  EXPECT_NEAR(s.accel_ratio_max, 100.0 / 200.0, 1e-6);
  // x_k - 3 x_k-1 + 3 x_k-2 - x_k-3 at the start: 0.5 a dt^2 (1) -> jerk a / (2 dt) = 50,000 mm/s^3.
  EXPECT_NEAR(s.jerk_ratio_max, 0.5, 1e-6);
}

TEST(PathScore, AReferenceThatNeverMovesScoresNothing) {
  std::vector<PathSample> rest(100, PathSample{{1.0, 1.0}, {0.0, 0.0}});
  rest[50].reference_mm = {5e-6, 0.0};  // telemetry rounding, not motion
  const PathScore s = score_path(line_program(), rest, fw::motion::MotionLimits{});
  EXPECT_EQ(s.window_samples, 0u);
  EXPECT_EQ(s.cycle_time_s, 0.0);
}

}  // namespace
}  // namespace tnv::hil
