// The motion core's producers and the cases they brought up: a profiled
// element (the S1 circle, the move) runs its time law exactly; a stop
// followed by new segments starts from rest; the joints of a straight line
// cost no speed; the jog producer's dead man and direction changes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "firmware/motion/jog_producer.hpp"
#include "firmware/motion/profiled_producers.hpp"
#include "tests/firmware/motion/motion_run.hpp"

namespace tnv::fw::motion {
namespace {

using test::MotionRun;
using test::configured;
using test::run_program;

TEST(MotionProfiled, TheCircleFollowsTheS1TimeLawTickForTick) {
  const CircleSpec spec{6.0, 2.0, 0.1, 0.0};
  const CircleTrajectory circle(spec);
  MotionInterpolator m = configured(circle_start_mm(spec, {0.0, 0.0}));
  ASSERT_EQ(m.push(circle_segment(spec, {0.0, 0.0})), SegmentRefusal::none);
  m.end_program();
  const auto ticks = static_cast<std::int64_t>(std::ceil(circle.duration_s() / 1e-3 - 1e-9));
  for (std::int64_t k = 0; k <= ticks; ++k) {
    const MotionReference r = m.tick();
    const PlaneSample now = circle.at(static_cast<double>(k) * 1e-3);
    const PlaneSample next = circle.at(static_cast<double>(k + 1) * 1e-3);
    for (std::size_t i = 0; i < 2; ++i) {
      ASSERT_NEAR(r.axis[i].position_mm, now.axis[i].position_mm, 1e-12) << "tick " << k << " axis " << i;
      ASSERT_NEAR(r.axis[i].speed_mm_s, now.axis[i].speed_mm_s, 1e-12) << "tick " << k;
      ASSERT_NEAR(r.axis[i].next_position_mm, next.axis[i].position_mm, 1e-12) << "tick " << k;
    }
    if (k < ticks) {
      ASSERT_EQ(r.state, MotionState::running) << "tick " << k;
    }
  }
  EXPECT_EQ(m.state(), MotionState::idle) << "done after the last tick of the time law";
  EXPECT_EQ(m.queued(), 0u);
  EXPECT_EQ(m.stats().segments_done, 1u);
}

TEST(MotionProfiled, AStopWarpsTimeAndRestsOnThePath) {
  const MoveSpec spec{hal::Axis::x, 20.0, 40.0, 0.05, 0.0};
  MotionInterpolator m = configured();
  ASSERT_EQ(m.push(move_segment(spec, {0.0, 0.0})), SegmentRefusal::none);
  m.end_program();
  double last_speed = 0.0;
  double peak_speed = 0.0;
  for (int k = 0; k < 200; ++k) {
    if (k == 100) m.stop();
    const MotionReference r = m.tick();
    EXPECT_EQ(r.axis[1].position_mm, 0.0) << "the other axis stays";
    peak_speed = std::max(peak_speed, r.axis[0].speed_mm_s);
    if (k > 101) {
      EXPECT_LE(r.axis[0].speed_mm_s, last_speed + 1e-12) << "decelerates through the stop, tick " << k;
    }
    last_speed = r.axis[0].speed_mm_s;
  }
  EXPECT_DOUBLE_EQ(peak_speed, 40.0);
  EXPECT_EQ(m.state(), MotionState::idle);
  EXPECT_EQ(last_speed, 0.0);
  // At the stop (t = 0.1 s) the move has covered its ramp (1 mm) and 50 ms
  // of cruise (2 mm); the warp's raised-cosine rate over the 50 ms ramp
  // time adds half of 50 ms at 40 mm/s: 4 mm.
  EXPECT_NEAR(m.reference_mm()[0], 4.0, 0.05);
}

TEST(MotionProfiled, BadRampsAreRefused) {
  MotionInterpolator m = configured();
  Segment s = line_to({10.0, 0.0}, 20.0);
  s.ramp_s = -0.1;
  EXPECT_EQ(m.push(s), SegmentRefusal::bad_ramp);
  s.ramp_s = 0.6;  // 20 mm/s x 0.6 s = 12 mm of ramps on 10 mm
  EXPECT_EQ(m.push(s), SegmentRefusal::bad_ramp);
  s.ramp_s = std::nan("");
  EXPECT_EQ(m.push(s), SegmentRefusal::not_finite);
  Segment d = dwell_for(1.0);
  d.ramp_s = 0.1;
  EXPECT_EQ(m.push(d), SegmentRefusal::bad_ramp);
  EXPECT_EQ(m.queued(), 0u);
}

TEST(MotionStop, NewSegmentsAfterAStopStartFromRestWithoutAJump) {
  MotionInterpolator m = configured();
  ASSERT_EQ(m.push(line_to({50.0, 0.0}, 40.0)), SegmentRefusal::none);
  std::vector<PlanePoint> path;
  for (int k = 0; k < 3000; ++k) {
    if (k == 300) m.stop();
    if (k == 700) {
      ASSERT_EQ(m.state(), MotionState::idle);
      ASSERT_EQ(m.push(line_to({m.queue_end_mm()[0], 10.0}, 10.0)), SegmentRefusal::none);
      m.end_program();
    }
    const MotionReference r = m.tick();
    path.push_back({r.axis[0].position_mm, r.axis[1].position_mm});
  }
  for (std::size_t k = 1; k < path.size(); ++k)
    for (std::size_t i = 0; i < 2; ++i)
      ASSERT_LE(std::fabs(path[k][i] - path[k - 1][i]), 40.0 * 1e-3 + 1e-12) << "tick " << k << " axis " << i;
  EXPECT_NEAR(path.back()[1], 10.0, 1e-9);
}

TEST(MotionStop, AStopDuringADwellEndsItOnceTheFilterHasSettled) {
  MotionInterpolator m = configured();
  ASSERT_EQ(m.push(dwell_for(5.0)), SegmentRefusal::none);
  ASSERT_EQ(m.push(line_to({10.0, 0.0}, 20.0)), SegmentRefusal::none);
  for (int k = 0; k < 100; ++k) m.tick();
  ASSERT_NE(m.state(), MotionState::idle) << "the dwell holds";
  m.stop();
  const std::size_t settle = m.derived().filter_taps;
  std::size_t ticks = 0;
  while (m.state() != MotionState::idle && ticks < 6000) {
    m.tick();
    ++ticks;
  }
  EXPECT_LE(ticks, settle + 2) << "a stop waited for the dwell's remainder";
  EXPECT_EQ(m.queued(), 0u);
}

// The number of ticks from the dwell's first tick to the first tick the
// line after it moves, with a feed hold of hold_ticks starting hold_at ticks
// into the dwell (none when hold_ticks is 0).
long dwell_to_motion_ticks(long hold_at, long hold_ticks, std::vector<MotionState>* states = nullptr) {
  MotionInterpolator m = configured();
  EXPECT_EQ(m.push(dwell_for(0.5)), SegmentRefusal::none);
  EXPECT_EQ(m.push(line_to({10.0, 0.0}, 20.0)), SegmentRefusal::none);
  m.end_program();
  for (long k = 0; k < 10'000; ++k) {
    if (hold_ticks > 0 && k == hold_at) m.hold();
    if (hold_ticks > 0 && k == hold_at + hold_ticks) m.resume();
    const MotionReference r = m.tick();
    if (states != nullptr) states->push_back(r.state);
    if (r.axis[0].next_position_mm != 0.0) return k;
  }
  return -1;
}

// A feed hold stops a dwell's clock: the remainder runs after the resume,
// so the dwell at rest is as long as programmed plus the time held (a
// deliberate deviation from LinuxCNC, whose task times G4 on the wall
// clock through a pause: docs/gcode.md "Feed hold").
TEST(MotionDwell, AFeedHoldStopsTheDwellsClockAndTheRemainderRunsAfterTheResume) {
  const long plain = dwell_to_motion_ticks(0, 0);
  ASSERT_GE(plain, 500) << "the dwell of 0.5 s rests 500 ticks at least";
  std::vector<MotionState> states;
  const long held = dwell_to_motion_ticks(200, 700, &states);
  EXPECT_EQ(held, plain + 700) << "the dwell ran on while held";
  for (long k = 200; k < 900; ++k) ASSERT_EQ(states[static_cast<std::size_t>(k)], MotionState::holding) << "tick " << k;
  // Held from 50 ticks before the dwell's end for longer than the dwell: the remainder still runs after it.
  const long late = dwell_to_motion_ticks(450, 2000);
  EXPECT_EQ(late, plain + 2000);
}

TEST(MotionJoints, AStraightLineInPiecesKeepsItsSpeedAtEveryJoint) {
  MotionInterpolator m = configured();
  std::vector<Segment> pieces;
  for (int i = 1; i <= 40; ++i) pieces.push_back(line_to({0.5 * i, 0.0}, 20.0));
  const MotionRun run = run_program(m, pieces);
  int cruising = 0;
  for (std::size_t k = 1; k < run.position_mm.size(); ++k) {
    const double v = (run.position_mm[k][0] - run.position_mm[k - 1][0]) / 1e-3;
    if (run.position_mm[k][0] > 3.0 && run.position_mm[k][0] < 17.0) {
      EXPECT_NEAR(v, 20.0, 1e-9) << "tick " << k << " at x = " << run.position_mm[k][0];
      ++cruising;
    }
  }
  EXPECT_GT(cruising, 600);
  EXPECT_EQ(m.stats().follower.brake_shortfalls, 0u);
  EXPECT_EQ(m.stats().follower.guard_failures, 0u);
}

std::array<JogLimits, hal::kAxisCount> jog_limits() { return hal::per_axis(JogLimits{50.0, 1000.0, 0.1}); }

TEST(JogProducer, CruisesAtTheCommandedSpeedAndTheDeadManStopsItOnThePath) {
  MotionInterpolator m = configured();
  JogProducer jog;
  jog.start(jog_limits());
  std::vector<PlanePoint> path;
  for (int k = 0; k < 400; ++k) {
    ASSERT_TRUE(jog.command(0, 15.0));
    ASSERT_TRUE(jog.command(1, 20.0));
    jog.produce(m);
    const MotionReference r = m.tick();
    path.push_back({r.axis[0].position_mm, r.axis[1].position_mm});
  }
  EXPECT_NEAR(m.path_speed_mm_s(), 25.0, 1e-9) << "|(15, 20)| mm/s";
  int k = 0;
  while (!(jog.idle() && m.state() == MotionState::idle) && k < 2000) {
    jog.produce(m);
    const MotionReference r = m.tick();
    path.push_back({r.axis[0].position_mm, r.axis[1].position_mm});
    ++k;
  }
  EXPECT_EQ(jog.deadman_stops(), 2u) << "one per axis";
  for (const PlanePoint& p : path) EXPECT_NEAR(p[0] * 20.0 - p[1] * 15.0, 0.0, 1e-9) << "on the line (15, 20)";
  EXPECT_LT(k, 400) << "ticks to rest after the last command";
  EXPECT_EQ(m.stats().underruns, 0u) << "the end of a jog is not an underrun";
}

TEST(JogProducer, ADirectionChangeGoesThroughRest) {
  MotionInterpolator m = configured();
  JogProducer jog;
  jog.start(jog_limits());
  double min_speed_after_change = 1e9;
  double y_at_change = 0.0;
  for (int k = 0; k < 800; ++k) {
    jog.command(0, k < 300 ? 20.0 : 0.0);
    jog.command(1, k < 300 ? 0.0 : 20.0);
    jog.produce(m);
    const MotionReference r = m.tick();
    if (k == 300) y_at_change = r.axis[1].position_mm;
    if (k > 300 && k < 500) min_speed_after_change = std::min(min_speed_after_change, m.path_speed_mm_s());
  }
  EXPECT_EQ(min_speed_after_change, 0.0) << "the path point rested before turning";
  EXPECT_EQ(y_at_change, 0.0);
  EXPECT_GT(m.reference_mm()[1], 1.0) << "then jogged along y";
}

TEST(JogProducer, RefusesNonFiniteOrTooFastCommandsAndStopsAtTheSoftLimit) {
  MotionLimits limits;
  limits.axis[0].position_max_mm = 2.0;
  MotionInterpolator m;
  ASSERT_STREQ(m.configure(limits, {0.0, 0.0}), "");
  JogProducer jog;
  jog.start(jog_limits());
  EXPECT_FALSE(jog.command(0, std::nan("")));
  EXPECT_FALSE(jog.command(0, 51.0));
  EXPECT_EQ(jog.target_mm_s(0), 0.0);
  for (int k = 0; k < 1000; ++k) {
    jog.command(0, 30.0);
    jog.produce(m);
    (void)m.tick();
  }
  EXPECT_LE(m.reference_mm()[0], 2.0);
  EXPECT_GT(m.reference_mm()[0], 2.0 - 1e-3) << "rests on the soft limit";
}

}  // namespace
}  // namespace tnv::fw::motion
