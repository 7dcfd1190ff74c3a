// The spindle's feed gate in the motion core (MotionInterpolator::
// set_feed_gate): shut, a feed move does not start and one running brakes
// to rest on the path; a rapid runs and, followed by a feed move, ends at
// rest; the gate opening lets the path go on. Limits hold throughout.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/firmware/motion/motion_run.hpp"

namespace tnv::fw::motion {
namespace {

using test::configured;
using test::run_program;

Segment rapid_to(PlanePoint end, double feed_mm_s) {
  Segment s = line_to(end, feed_mm_s);
  s.rapid = true;
  return s;
}

TEST(FeedGate, AShutGateHoldsAFeedMoveAtRestAndOpeningItRunsIt) {
  MotionInterpolator m = configured();
  m.set_feed_gate(false);
  ASSERT_EQ(m.push(line_to({5.0, 0.0}, 10.0)), SegmentRefusal::none);
  m.end_program();
  for (int k = 0; k < 500; ++k) {
    const MotionReference r = m.tick();
    ASSERT_EQ(r.axis[0].next_position_mm, 0.0) << "tick " << k;
  }
  EXPECT_TRUE(m.waiting_for_feed_gate());
  m.set_feed_gate(true);
  const test::MotionRun run = run_program(m, {}, 100'000);
  EXPECT_NEAR(m.reference_mm()[0], 5.0, 1e-9);
  EXPECT_FALSE(m.waiting_for_feed_gate());
  EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-9);
}

TEST(FeedGate, ARapidRunsAndAFeedMoveAfterItWaitsAtItsEndAtRest) {
  MotionInterpolator m = configured();
  m.set_feed_gate(false);
  ASSERT_EQ(m.push(rapid_to({4.0, 0.0}, 40.0)), SegmentRefusal::none);
  ASSERT_EQ(m.push(line_to({8.0, 0.0}, 10.0)), SegmentRefusal::none);
  m.end_program();
  double last = 0.0;
  double speed_at_end = 1.0;
  for (int k = 0; k < 3000; ++k) {
    const MotionReference r = m.tick();
    ASSERT_LE(r.axis[0].next_position_mm, 4.0 + 1e-9) << "the feed move began at tick " << k;
    last = r.axis[0].next_position_mm;
    speed_at_end = r.axis[0].next_speed_mm_s;
  }
  EXPECT_NEAR(last, 4.0, 1e-9) << "the rapid ran to its end";
  EXPECT_EQ(speed_at_end, 0.0) << "and rests there";
  EXPECT_TRUE(m.waiting_for_feed_gate());
  m.set_feed_gate(true);
  run_program(m, {}, 100'000);
  EXPECT_NEAR(m.reference_mm()[0], 8.0, 1e-9);
}

TEST(FeedGate, ShuttingItMidFeedBrakesOnThePathWithinTheLimits) {
  MotionInterpolator m = configured();
  const test::MotionRun run = run_program(
      m, {line_to({20.0, 0.0}, 20.0)}, 100'000, [](std::size_t k, MotionInterpolator& mi) {
        if (k == 400) mi.set_feed_gate(false);
        if (k == 1400) mi.set_feed_gate(true);
      });
  // Stopped somewhere on the line for a while, then on to its end.
  std::size_t still = 0;
  for (std::size_t k = 500; k < 1400 && k < run.position_mm.size(); ++k)
    if (run.position_mm[k] == run.position_mm[k - 1]) ++still;
  EXPECT_GT(still, 500u) << "the path did not wait while the gate was shut";
  EXPECT_NEAR(run.position_mm.back()[0], 20.0, 1e-9);
  EXPECT_EQ(run.position_mm[1000][1], 0.0) << "it stays on the path";
  EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-9);
  EXPECT_LE(run.jerk_ratio_max, 1.0 + 1e-9);
}

TEST(FeedGate, AProfiledElementWaitsForTheGate) {
  MotionInterpolator m = configured();
  m.set_feed_gate(false);
  Segment move = line_to({3.0, 0.0}, 5.0);
  move.ramp_s = 0.05;  // a profiled element (the MOVE / circle producers)
  ASSERT_EQ(m.push(move), SegmentRefusal::none);
  for (int k = 0; k < 300; ++k) ASSERT_EQ(m.tick().axis[0].next_position_mm, 0.0);
  EXPECT_FALSE(m.profiled_running());
  m.set_feed_gate(true);
  run_program(m, {}, 100'000);
  EXPECT_NEAR(m.reference_mm()[0], 3.0, 1e-9);
}

}  // namespace
}  // namespace tnv::fw::motion
