#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "tests/firmware/motion/motion_run.hpp"

namespace tnv::fw::motion {
namespace {

using test::MotionRun;
using test::configured;
using test::run_program;

TEST(SegmentQueueRefusal, BadSegmentsAreRefusedWithAReasonAndTheQueueIsUnchanged) {
  MotionInterpolator m = configured();
  ASSERT_EQ(m.push(line_to({10.0, 0.0}, 10.0)), SegmentRefusal::none);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    Segment s;
    SegmentRefusal why;
  };
  const Case cases[] = {
      {line_to({nan, 0.0}, 10.0), SegmentRefusal::not_finite},
      {line_to({10.0, 0.0}, 10.0), SegmentRefusal::zero_length},
      {line_to({10.0, 5.0}, 0.0), SegmentRefusal::feed_not_positive},
      {line_to({10.0, 5.0}, -1.0), SegmentRefusal::feed_not_positive},
      {line_to({20.0, 0.0}, 150.0), SegmentRefusal::feed_above_limit},
      {line_to({300.0, 0.0}, 10.0), SegmentRefusal::outside_workspace},
      {arc_to(false, {20.0, 1.0}, {15.0, 0.0}, 10.0), SegmentRefusal::arc_radius_mismatch},
      {arc_to(true, {10.0, 0.0}, {10.0, 0.001}, 10.0), SegmentRefusal::arc_radius_too_small},
      {dwell_for(-1.0), SegmentRefusal::bad_dwell},
      {dwell_for(nan), SegmentRefusal::not_finite},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(m.push(c.s), c.why) << to_string(c.why);
    EXPECT_EQ(m.queued(), 1u) << "a refused " << to_string(c.why) << " segment changed the queue";
  }
  // The next good segment still starts where the first one ended.
  ASSERT_EQ(m.push(line_to({10.0, 10.0}, 10.0)), SegmentRefusal::none);
  m.end_program();
  PlanePoint last{};
  for (int k = 0; k < 20000; ++k) {
    const MotionReference r = m.tick();
    last = {r.axis[0].position_mm, r.axis[1].position_mm};
  }
  EXPECT_NEAR(last[0], 10.0, 1e-9);
  EXPECT_NEAR(last[1], 10.0, 1e-9);
}

TEST(SegmentQueueRefusal, AFullQueueRefusesAndKeepsItsSegments) {
  MotionInterpolator m = configured();
  for (std::size_t i = 0; i < kSegmentQueueCapacity; ++i)
    ASSERT_EQ(m.push(line_to({static_cast<double>(i + 1), static_cast<double>(i % 2)}, 10.0)), SegmentRefusal::none);
  EXPECT_EQ(m.free_slots(), 0u);
  EXPECT_EQ(m.push(line_to({100.0, 0.0}, 10.0)), SegmentRefusal::queue_full);
  EXPECT_EQ(m.queued(), kSegmentQueueCapacity);
}

TEST(MotionCorners, BlendedCornersStayWithinThePathTolerance) {
  const MotionLimits limits{};
  for (double feed : {5.0, 30.0, 80.0}) {
    MotionInterpolator m = configured();
    // 90, 45 and 150 degree turns and a shallow 10 degree one.
    const std::vector<PlanePoint> corners = {{0, 0}, {20, 0}, {20, 20}, {40, 40}, {20, 45}, {0, 48.5}};
    std::vector<Segment> program;
    for (std::size_t i = 1; i < corners.size(); ++i) program.push_back(line_to(corners[i], feed));
    const MotionRun run = run_program(m, program);
    EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-6);
    EXPECT_LE(run.jerk_ratio_max, 1.0 + 1e-6);
    const double dev = test::polyline_deviation_max_mm(run, corners);
    EXPECT_LE(dev, limits.path_tolerance_mm) << "feed " << feed << ": corner blend " << dev * 1e3 << " um off the path";
  }
}

TEST(MotionCorners, ExactStopComesToRestAtTheCorner) {
  MotionInterpolator m = configured();
  Segment first = line_to({10.0, 0.0}, 20.0);
  first.exact_stop = true;
  const MotionRun run = run_program(m, {first, line_to({10.0, 10.0}, 20.0)});
  std::size_t resting_at_corner = 0;
  for (std::size_t k = 1; k < run.position_mm.size(); ++k) {
    const PlanePoint& p = run.position_mm[k];
    if (p == run.position_mm[k - 1] && std::fabs(p[0] - 10.0) < 1e-12 && std::fabs(p[1]) < 1e-12) ++resting_at_corner;
  }
  EXPECT_GE(resting_at_corner, 1u) << "the reference never rested exactly on the corner";
  EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(run.jerk_ratio_max, 1.0 + 1e-6);
}

TEST(MotionArcs, ArcsAndAFullCircleKeepTheLimitsAndTheRadius) {
  MotionInterpolator m = configured({10.0, 0.0});
  const std::vector<Segment> program = {
      arc_to(false, {10.0, 0.0}, {0.0, 0.0}, 20.0),   // full ccw circle r = 10
      arc_to(true, {14.0, 0.0}, {12.0, 0.0}, 20.0),   // cw half circle r = 2, tangent
      line_to({14.0, -5.0}, 20.0)};
  const MotionRun run = run_program(m, program);
  EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(run.jerk_ratio_max, 1.0 + 1e-6);
  EXPECT_EQ(m.stats().follower.guard_failures, 0u);
  // While on the big circle (the first ~pi*10 s), the radius stays within the tolerance.
  double worst = 0.0;
  for (std::size_t k = 300; k < 2800; ++k) {
    const PlanePoint& p = run.position_mm[k];
    worst = std::max(worst, std::fabs(std::hypot(p[0], p[1]) - 10.0));
  }
  EXPECT_LE(worst, MotionLimits{}.path_tolerance_mm) << worst * 1e3 << " um radius error";
}

TEST(MotionOverride, OverrideChangesMidPathKeepTheLimitsAndScaleTheSpeed) {
  MotionInterpolator m = configured();
  double speed_at_150 = 0.0;
  double speed_at_30 = 0.0;
  const MotionRun run = run_program(
      m, {line_to({200.0, 0.0}, 40.0), line_to({200.0, 100.0}, 40.0)}, 100000, [&](std::size_t k, MotionInterpolator& mi) {
        if (k == 500) { EXPECT_TRUE(mi.set_feed_override(1.5)); }
        if (k == 1500) { EXPECT_TRUE(mi.set_feed_override(0.3)); }
        if (k == 1499) speed_at_150 = mi.path_speed_mm_s();
        if (k == 2999) speed_at_30 = mi.path_speed_mm_s();
      });
  EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(run.jerk_ratio_max, 1.0 + 1e-6);
  EXPECT_NEAR(speed_at_150, 60.0, 1e-9);
  EXPECT_NEAR(speed_at_30, 12.0, 1e-9);
  EXPECT_FALSE(m.set_feed_override(1.6));
  EXPECT_FALSE(m.set_feed_override(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_EQ(m.feed_override(), 0.3);
}

TEST(MotionUnderrun, RunningDryStopsOnThePathCountsOnceAndResumes) {
  MotionInterpolator m = configured();
  ASSERT_EQ(m.push(line_to({10.0, 0.0}, 30.0)), SegmentRefusal::none);
  std::vector<PlanePoint> samples;
  for (int k = 0; k < 3000; ++k) {
    const MotionReference r = m.tick();
    samples.push_back({r.axis[0].position_mm, r.axis[1].position_mm});
  }
  EXPECT_EQ(m.stats().underruns, 1u);
  EXPECT_EQ(m.state(), MotionState::starved);
  EXPECT_NEAR(samples.back()[0], 10.0, 1e-12) << "stopped before the end of the queued path";
  for (const PlanePoint& p : samples) EXPECT_LE(p[0], 10.0 + 1e-12) << "ran past the queued path";
  ASSERT_EQ(m.push(line_to({10.0, 10.0}, 30.0)), SegmentRefusal::none);
  m.end_program();
  for (int k = 0; k < 3000; ++k) m.tick();
  EXPECT_EQ(m.state(), MotionState::idle);
  EXPECT_EQ(m.stats().underruns, 1u) << "the program's end is not an underrun";
}

TEST(MotionStop, ControlledStopBrakesOnThePathAndDropsTheQueue) {
  MotionInterpolator m = configured();
  std::vector<PlanePoint> corners = {{0, 0}, {50, 0}, {50, 50}};
  const MotionRun run = run_program(
      m, {line_to(corners[1], 50.0), line_to(corners[2], 50.0)}, 100000,
      [&](std::size_t k, MotionInterpolator& mi) {
        if (k == 600) mi.stop();
      });
  EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(run.jerk_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(test::polyline_deviation_max_mm(run, corners), 1e-9);
  EXPECT_LT(run.position_mm.back()[0], 50.0) << "did not stop before the corner";
  EXPECT_EQ(m.queued(), 0u);
  EXPECT_EQ(m.state(), MotionState::idle);
}

TEST(MotionPlanner, BackwardPassWorkPerTickIsBounded) {
  MotionInterpolator m = configured();
  std::vector<Segment> zigzag;
  for (int i = 1; i <= 400; ++i) zigzag.push_back(line_to({0.5 * i, (i % 2) * 0.05}, 20.0));
  const MotionRun run = run_program(m, zigzag);
  EXPECT_LE(m.stats().max_replan_examined, kReplanBudgetSegments);
  EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(run.jerk_ratio_max, 1.0 + 1e-6);
}

}  // namespace
}  // namespace tnv::fw::motion
