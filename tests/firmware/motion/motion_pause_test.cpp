// The program pause in the motion core (Segment::pause, M0 / M1 / M6): the
// element before it ends at rest, the core reports paused only once the
// reference rests, holds there however long, and goes on only after
// release_pause(); a feed hold or a stop is not a release, and a stop while
// paused drops the pause with the queue.
#include <gtest/gtest.h>

#include <algorithm>

#include "tests/firmware/motion/motion_run.hpp"

namespace tnv::fw::motion {
namespace {

using test::configured;
using test::run_program;

// Ticks until the state is `s` (at most `limit`); the number of ticks, or -1.
long ticks_until(MotionInterpolator& m, MotionState s, long limit = 100'000) {
  for (long k = 0; k < limit; ++k)
    if (m.tick().state == s) return k;
  return -1;
}

TEST(ProgramPause, TheQueueTakesAPauseAndRefusesAPauseWithATimeOrOnALine) {
  MotionInterpolator m = configured();
  EXPECT_EQ(m.push(pause_here(3)), SegmentRefusal::none);
  Segment timed = pause_here();
  timed.dwell_s = 1.0;
  EXPECT_EQ(m.push(timed), SegmentRefusal::bad_dwell);
  Segment line = line_to({1.0, 0.0}, 5.0);
  line.pause = true;
  EXPECT_EQ(m.push(line), SegmentRefusal::bad_kind);
  EXPECT_EQ(m.queued(), 1u) << "the refusals left the queue as it was";
}

TEST(ProgramPause, ReachedAtRestAndHeldUntilReleased) {
  MotionInterpolator m = configured();
  ASSERT_EQ(m.push(line_to({5.0, 0.0}, 20.0, 1)), SegmentRefusal::none);
  ASSERT_EQ(m.push(pause_here(2)), SegmentRefusal::none);
  ASSERT_EQ(m.push(line_to({10.0, 0.0}, 20.0, 3)), SegmentRefusal::none);
  m.end_program();
  EXPECT_FALSE(m.release_pause()) << "not paused yet: nothing to release";
  ASSERT_GE(ticks_until(m, MotionState::paused), 0) << "never paused";
  EXPECT_TRUE(m.at_rest());
  const double paused_at = m.reference_mm()[0];
  EXPECT_NEAR(paused_at, 5.0, 1e-12) << "paused at the line's end";
  for (int k = 0; k < 5000; ++k) {
    const MotionReference r = m.tick();
    ASSERT_EQ(r.state, MotionState::paused) << "tick " << k;
    ASSERT_EQ(r.axis[0].next_position_mm, paused_at);
    ASSERT_EQ(r.axis[0].next_speed_mm_s, 0.0);
    ASSERT_EQ(r.tag, 2u) << "the pause's tag is reported while it holds";
  }
  const std::uint64_t done_before = m.stats().segments_done;
  EXPECT_EQ(m.stats().underruns, 0u);
  m.resume();  // a feed resume is not the operator's continue
  for (int k = 0; k < 100; ++k) ASSERT_EQ(m.tick().state, MotionState::paused);
  ASSERT_TRUE(m.release_pause());
  const test::MotionRun run = run_program(m, {}, 100'000);
  EXPECT_NEAR(m.reference_mm()[0], 10.0, 1e-9);
  EXPECT_EQ(m.stats().segments_done, done_before + 2) << "the pause and the last line";
  EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-9);
  EXPECT_LE(run.jerk_ratio_max, 1.0 + 1e-9);
}

TEST(ProgramPause, TheElementBeforeItEndsAtRestNotBlendedThroughIt) {
  MotionInterpolator m = configured();
  ASSERT_EQ(m.push(line_to({5.0, 0.0}, 20.0)), SegmentRefusal::none);
  ASSERT_EQ(m.push(pause_here()), SegmentRefusal::none);
  ASSERT_EQ(m.push(line_to({5.0, 5.0}, 20.0)), SegmentRefusal::none);
  m.end_program();
  double max_y_before_pause = 0.0;
  for (int k = 0; k < 100'000; ++k) {
    const MotionReference r = m.tick();
    if (r.state == MotionState::paused) break;
    max_y_before_pause = std::max(max_y_before_pause, r.axis[1].next_position_mm);
  }
  ASSERT_EQ(m.state(), MotionState::paused);
  EXPECT_EQ(max_y_before_pause, 0.0) << "the corner was not rounded: y began before the pause";
}

TEST(ProgramPause, AHoldWhilePausedShowsHoldingAndTheReleaseWaitsForTheResume) {
  MotionInterpolator m = configured();
  ASSERT_EQ(m.push(line_to({2.0, 0.0}, 20.0)), SegmentRefusal::none);
  ASSERT_EQ(m.push(pause_here()), SegmentRefusal::none);
  ASSERT_EQ(m.push(line_to({4.0, 0.0}, 20.0)), SegmentRefusal::none);
  m.end_program();
  ASSERT_GE(ticks_until(m, MotionState::paused), 0);
  m.hold();
  EXPECT_EQ(m.tick().state, MotionState::holding);
  EXPECT_FALSE(m.release_pause()) << "held: the operator resumes the hold first";
  m.resume();
  EXPECT_EQ(m.tick().state, MotionState::paused);
  ASSERT_TRUE(m.release_pause());
  run_program(m, {}, 100'000);
  EXPECT_NEAR(m.reference_mm()[0], 4.0, 1e-9);
}

TEST(ProgramPause, AStopWhilePausedDropsThePauseAndTheRest) {
  MotionInterpolator m = configured();
  ASSERT_EQ(m.push(line_to({2.0, 0.0}, 20.0)), SegmentRefusal::none);
  ASSERT_EQ(m.push(pause_here()), SegmentRefusal::none);
  ASSERT_EQ(m.push(line_to({4.0, 0.0}, 20.0)), SegmentRefusal::none);
  ASSERT_GE(ticks_until(m, MotionState::paused), 0);
  m.stop();
  ASSERT_GE(ticks_until(m, MotionState::idle, 1000), 0) << "the stop did not end the program";
  EXPECT_EQ(m.queued(), 0u);
  for (int k = 0; k < 1000; ++k) ASSERT_NEAR(m.tick().axis[0].next_position_mm, 2.0, 1e-12);
}

TEST(ProgramPause, AReleaseAskedThenAStopBeforeTheTickRunsNothingMore) {
  MotionInterpolator m = configured();
  ASSERT_EQ(m.push(line_to({2.0, 0.0}, 20.0)), SegmentRefusal::none);
  ASSERT_EQ(m.push(pause_here()), SegmentRefusal::none);
  ASSERT_EQ(m.push(line_to({4.0, 0.0}, 20.0)), SegmentRefusal::none);
  ASSERT_GE(ticks_until(m, MotionState::paused), 0);
  ASSERT_TRUE(m.release_pause());
  m.stop();
  for (int k = 0; k < 2000; ++k) ASSERT_NEAR(m.tick().axis[0].next_position_mm, 2.0, 1e-12) << "tick " << k;
  EXPECT_EQ(m.state(), MotionState::idle);
}

}  // namespace
}  // namespace tnv::fw::motion
