#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/firmware/motion/motion_run.hpp"

namespace tnv::fw::motion {
namespace {

using test::MotionRun;
using test::run_program;

std::vector<Segment> square(double side_mm, double feed_mm_s) {
  return {line_to({side_mm, 0.0}, feed_mm_s), line_to({side_mm, side_mm}, feed_mm_s),
          line_to({0.0, side_mm}, feed_mm_s), line_to({0.0, 0.0}, feed_mm_s)};
}

std::vector<Segment> chord_circle(double radius_mm, double chord_mm, double feed_mm_s) {
  std::vector<Segment> out;
  const int n = static_cast<int>(std::ceil(2.0 * std::numbers::pi * radius_mm / chord_mm));
  out.push_back(line_to({radius_mm, 0.0}, feed_mm_s));
  for (int i = 1; i <= n; ++i) {
    const double th = 2.0 * std::numbers::pi * i / n;
    out.push_back(line_to({radius_mm * std::cos(th), radius_mm * std::sin(th)}, feed_mm_s));
  }
  return out;
}

void expect_within_limits(const MotionRun& run, const char* what) {
  EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-6) << what << ": commanded acceleration above the axis limit";
  EXPECT_LE(run.jerk_ratio_max, 1.0 + 1e-6) << what << ": commanded jerk above the axis limit";
  EXPECT_LE(run.speed_ratio_max, 1.0 + 1e-6) << what << ": commanded speed above the axis limit";
  EXPECT_GT(run.motion_ticks, 0u) << what << ": nothing moved";
}

TEST(MotionLimits, SquareCornersKeepAccelerationAndJerkWithinLimitsAtEveryFeed) {
  for (double feed : {2.0, 20.0, 60.0, 100.0}) {
    MotionInterpolator m;
    ASSERT_STREQ(m.configure({}, {0.0, 0.0}), "");
    const MotionRun run = run_program(m, square(20.0, feed));
    expect_within_limits(run, "square");
    EXPECT_EQ(m.stats().follower.guard_failures, 0u);
    EXPECT_EQ(m.stats().follower.brake_shortfalls, 0u);
    double max_x = 0.0, max_y = 0.0;
    for (const PlanePoint& p : run.position_mm) {
      max_x = std::max(max_x, p[0]);
      max_y = std::max(max_y, p[1]);
    }
    EXPECT_GT(max_x, 20.0 - 0.005) << "feed " << feed << ": the square was not run to its corners";
    EXPECT_GT(max_y, 20.0 - 0.005) << "feed " << feed;
    EXPECT_NEAR(std::hypot(run.position_mm.back()[0], run.position_mm.back()[1]), 0.0, 1e-9);
    // Ramps use a quarter of the jerk limit (half the acceleration budget
    // through a filter sized for a full reversal): it must show.
    EXPECT_GT(run.jerk_ratio_max, 0.2) << "feed " << feed;
  }
}

TEST(MotionLimits, ChordCircleAtTwentyKeepsFeedRatioAboveNinetyPercent) {
  MotionInterpolator m;
  ASSERT_STREQ(m.configure({}, {0.0, 0.0}), "");
  const std::vector<Segment> program = chord_circle(10.0, 0.1, 20.0);
  const MotionRun run = run_program(m, program);
  expect_within_limits(run, "0.1 mm chord circle");
  const double length_mm = 10.0 + 2.0 * std::numbers::pi * 10.0;  // approach line + circle (chords ~ circle)
  const double cycle_s = static_cast<double>(run.motion_ticks) * 1e-3;
  const double feed_ratio = (length_mm / 20.0) / cycle_s;
  EXPECT_GE(feed_ratio, 0.9) << "cycle " << cycle_s << " s";
  RecordProperty("feed_ratio", std::to_string(feed_ratio));
}

TEST(MotionLimits, LongSegmentReachesTheProgrammedFeed) {
  MotionInterpolator m;
  ASSERT_STREQ(m.configure({}, {0.0, 0.0}), "");
  double top_speed = 0.0;
  const MotionRun run = run_program(m, {line_to({100.0, 50.0}, 40.0)});
  expect_within_limits(run, "long line");
  MotionInterpolator m2;
  ASSERT_STREQ(m2.configure({}, {0.0, 0.0}), "");
  m2.push(line_to({100.0, 50.0}, 40.0));
  m2.end_program();
  for (int k = 0; k < 10000; ++k) {
    const MotionReference r = m2.tick();
    top_speed = std::max(top_speed, std::hypot(r.axis[0].speed_mm_s, r.axis[1].speed_mm_s));
  }
  EXPECT_NEAR(top_speed, 40.0, 1e-6) << "path speed must reach F on a long line";
}

}  // namespace
}  // namespace tnv::fw::motion
