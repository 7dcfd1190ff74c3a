// A program's spindle command in the motion core (Segment::spindle: S, M3,
// M4, M5): the element before it ends at rest, the core offers it
// (spindle_change_due) only once the reference rests, holds it at the
// front until the tick task says it is done, and then goes on; a hold
// keeps it waiting, a stop drops it. The queue refuses a spindle command
// on a line, with a time, with a pause, or a start at no speed.
#include <gtest/gtest.h>

#include "tests/firmware/motion/motion_run.hpp"

namespace tnv::fw::motion {
namespace {

using test::configured;
using test::run_program;

// Ticks until a spindle change is due (at most `limit`); the number of ticks, or -1.
long ticks_until_due(MotionInterpolator& m, long limit = 100'000) {
  for (long k = 0; k < limit; ++k) {
    m.tick();
    if (m.spindle_change_due() != nullptr) return k;
  }
  return -1;
}

TEST(ProgramSpindleChange, TheQueueRefusesWhatIsNotASpindleCommand) {
  MotionInterpolator m = configured();
  Segment on_line = line_to({1.0, 0.0}, 5.0);
  on_line.spindle = SpindleChange::forward;
  on_line.spindle_rpm = 1000.0;
  EXPECT_EQ(m.push(on_line), SegmentRefusal::bad_kind);
  Segment timed = spindle_here(SpindleChange::forward, 1000.0);
  timed.dwell_s = 0.5;
  EXPECT_EQ(m.push(timed), SegmentRefusal::bad_dwell);
  Segment both = spindle_here(SpindleChange::stop, 0.0);
  both.pause = true;
  EXPECT_EQ(m.push(both), SegmentRefusal::bad_kind);
  EXPECT_EQ(m.push(spindle_here(SpindleChange::reverse, 0.0)), SegmentRefusal::bad_spindle);
  EXPECT_EQ(m.push(spindle_here(SpindleChange::forward, -5.0)), SegmentRefusal::bad_spindle);
  EXPECT_EQ(m.queued(), 0u) << "the refusals left the queue as it was";
  EXPECT_EQ(m.push(spindle_here(SpindleChange::forward, 1000.0)), SegmentRefusal::none);
  EXPECT_EQ(m.push(spindle_here(SpindleChange::stop, 0.0)), SegmentRefusal::none);
}

TEST(ProgramSpindleChange, DueOnlyAtRestAndHeldUntilDone) {
  MotionInterpolator m = configured();
  ASSERT_EQ(m.push(line_to({5.0, 0.0}, 20.0, 1)), SegmentRefusal::none);
  ASSERT_EQ(m.push(spindle_here(SpindleChange::reverse, 2500.0, 2)), SegmentRefusal::none);
  ASSERT_EQ(m.push(line_to({5.0, 5.0}, 20.0, 3)), SegmentRefusal::none);
  m.end_program();
  EXPECT_EQ(m.spindle_change_due(), nullptr) << "not yet reached";
  ASSERT_GE(ticks_until_due(m), 0) << "never due";
  EXPECT_TRUE(m.at_rest());
  const double at_x = m.reference_mm()[0];
  EXPECT_NEAR(at_x, 5.0, 1e-12) << "due at the line's end, at rest";
  EXPECT_EQ(m.reference_mm()[1], 0.0) << "not blended into the next line";
  const Segment* due = m.spindle_change_due();
  ASSERT_NE(due, nullptr);
  EXPECT_EQ(due->spindle, SpindleChange::reverse);
  EXPECT_EQ(due->spindle_rpm, 2500.0);
  EXPECT_EQ(due->tag, 2u);
  for (int k = 0; k < 500; ++k) {
    const MotionReference r = m.tick();
    ASSERT_EQ(r.axis[0].next_position_mm, at_x) << "moved on before the change was done, tick " << k;
    ASSERT_NE(m.spindle_change_due(), nullptr);
  }
  m.spindle_change_done();
  m.tick();
  EXPECT_EQ(m.spindle_change_due(), nullptr) << "dropped at the next tick";
  run_program(m, {}, 100'000);
  EXPECT_NEAR(m.reference_mm()[1], 5.0, 1e-9) << "the line after it ran";
}

TEST(ProgramSpindleChange, AHoldKeepsItWaitingAndAStopDropsIt) {
  MotionInterpolator m = configured();
  ASSERT_EQ(m.push(line_to({2.0, 0.0}, 20.0)), SegmentRefusal::none);
  ASSERT_EQ(m.push(spindle_here(SpindleChange::forward, 1000.0)), SegmentRefusal::none);
  ASSERT_EQ(m.push(line_to({4.0, 0.0}, 20.0)), SegmentRefusal::none);
  m.hold();
  for (int k = 0; k < 5000; ++k) {
    m.tick();
    ASSERT_EQ(m.spindle_change_due(), nullptr) << "due during a feed hold, tick " << k;
  }
  m.resume();
  ASSERT_GE(ticks_until_due(m), 0);
  m.stop();
  EXPECT_EQ(m.spindle_change_due(), nullptr) << "a stop: nothing more is carried out";
  for (int k = 0; k < 100; ++k) m.tick();
  EXPECT_EQ(m.queued(), 0u);
  EXPECT_EQ(m.state(), MotionState::idle);
}

}  // namespace
}  // namespace tnv::fw::motion
