// Probe moves in the motion core (Segment::probe, G38.2-G38.5) with a fake
// probe input that follows the reference: the trip brakes the line to rest
// within its braking distance and the next element starts there; an
// untripped end goes on or stops the program as the kind demands; a probe
// whose input already is in the tripping state is refused; nothing may be
// queued behind a probe until its outcome.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "tests/firmware/motion/motion_run.hpp"

namespace tnv::fw::motion {
namespace {

using test::configured;

struct ProbeRunResult {
  ProbeOutcome outcome = ProbeOutcome::none;
  long trip_tick = -1;
  double trip_reference_x_mm = 0.0;  // x_ref,k in the tick that saw the trip
  double max_x_mm = 0.0;
  long ticks = 0;
};

// Ticks until the probe's outcome; the input is touching(x) of the reference
// x_ref,k of the tick before (as a table one tick behind would give it).
ProbeRunResult run_until_outcome(MotionInterpolator& m, const std::function<bool(double)>& touching,
                                 long limit = 100'000) {
  ProbeRunResult out;
  double x_mm = m.reference_mm()[0];
  for (long k = 0; k < limit; ++k) {
    m.set_probe_input(touching(x_mm));
    const MotionReference r = m.tick();
    if (m.probe_tripped_now()) {
      out.trip_tick = k;
      out.trip_reference_x_mm = x_mm;
    }
    x_mm = r.axis[0].position_mm;
    out.max_x_mm = std::max(out.max_x_mm, r.axis[0].next_position_mm);
    if (m.probe_outcome() != ProbeOutcome::none) {
      out.outcome = m.probe_outcome();
      out.ticks = k;
      return out;
    }
  }
  return out;
}

// Ticks until at rest with nothing queued.
void run_to_rest(MotionInterpolator& m, bool input = false) {
  for (long k = 0; k < 100'000 && !(m.queued() == 0 && m.at_rest() && k > 4); ++k) {
    m.set_probe_input(input);
    m.tick();
  }
}

constexpr double kFeed_mm_s = 5.0;
constexpr double kContact_mm = 3.0;

TEST(ProbeMove, TheTripBrakesTheLineToRestWithinItsBrakingDistanceAndTheNextElementStartsThere) {
  MotionInterpolator m = configured();
  ASSERT_EQ(m.push(probe_to(ProbeKind::toward_or_error, {10.0, 0.0}, kFeed_mm_s, 7)), SegmentRefusal::none);
  const ProbeRunResult r = run_until_outcome(m, [](double x) { return x >= kContact_mm; });
  ASSERT_EQ(r.outcome, ProbeOutcome::tripped);
  ASSERT_GE(r.trip_tick, 0) << "no tick reported the trip";
  EXPECT_GE(r.trip_reference_x_mm, kContact_mm) << "tripped before contact";
  // Past the contact: the input's age (v dt each: the tick before, and
  // x_ref,k is two ticks behind the filter's newest output), the jerk filter's
  // delay (the path point runs (taps - 1) / 2 ticks ahead of the reference
  // the input follows) and the path point's braking from the feed at the
  // path acceleration, v^2 / 2a plus a tick.
  const double a = m.derived().path_accel_mm_s2;
  const double dt = m.limits().tick_period_s;
  const double filter_delay_mm = kFeed_mm_s * 0.5 * static_cast<double>(m.derived().filter_taps - 1) * dt;
  const double braking_mm = kFeed_mm_s * kFeed_mm_s / (2.0 * a) + kFeed_mm_s * dt;
  EXPECT_LE(r.max_x_mm, kContact_mm + 3.0 * kFeed_mm_s * dt + filter_delay_mm + braking_mm + 1e-9)
      << "ran " << (r.max_x_mm - kContact_mm) * 1e3 << " um past the contact";
  EXPECT_LT(r.max_x_mm, 10.0 - 1.0) << "the rest of the line was not dropped";
  EXPECT_TRUE(m.at_rest());
  EXPECT_EQ(m.queued(), 0u);
  EXPECT_EQ(m.state(), MotionState::starved) << "the program stays open for the host's next element";
  EXPECT_NEAR(m.queue_end_mm()[0], m.reference_mm()[0], 1e-12) << "the next element starts where the probe rests";
  EXPECT_EQ(m.stats().underruns, 0u) << "waiting after a probe is no underrun";
  // The program goes on from there.
  ASSERT_EQ(m.push(line_to({0.0, 0.0}, 20.0)), SegmentRefusal::none);
  m.end_program();
  run_to_rest(m, true);
  EXPECT_NEAR(m.reference_mm()[0], 0.0, 1e-9);
  EXPECT_EQ(m.state(), MotionState::idle);
}

TEST(ProbeMove, NothingIsQueuedBehindAProbeUntilItsOutcome) {
  MotionInterpolator m = configured();
  ASSERT_EQ(m.push(probe_to(ProbeKind::toward, {10.0, 0.0}, kFeed_mm_s)), SegmentRefusal::none);
  EXPECT_TRUE(m.probe_pending());
  EXPECT_EQ(m.push(line_to({0.0, 5.0}, 20.0)), SegmentRefusal::probe_pending);
  EXPECT_EQ(m.queued(), 1u) << "the refusal queued nothing";
  EXPECT_EQ(m.queue_end_mm()[0], 10.0);
}

TEST(ProbeMove, OnlyAFeedLineEndingAtRestIsAProbe) {
  MotionInterpolator m = configured();
  Segment rapid = probe_to(ProbeKind::toward, {10.0, 0.0}, kFeed_mm_s);
  rapid.rapid = true;
  EXPECT_EQ(m.push(rapid), SegmentRefusal::bad_kind);
  Segment arc = arc_to(true, {2.0, 0.0}, {1.0, 0.0}, kFeed_mm_s);
  arc.probe = ProbeKind::toward;
  arc.exact_stop = true;
  EXPECT_EQ(m.push(arc), SegmentRefusal::bad_kind);
  Segment blended = probe_to(ProbeKind::toward, {10.0, 0.0}, kFeed_mm_s);
  blended.exact_stop = false;
  EXPECT_EQ(m.push(blended), SegmentRefusal::bad_kind);
  Segment unknown = probe_to(ProbeKind::toward, {10.0, 0.0}, kFeed_mm_s);
  unknown.probe = static_cast<ProbeKind>(9);
  EXPECT_EQ(m.push(unknown), SegmentRefusal::bad_kind);
  EXPECT_EQ(m.queued(), 0u);
  EXPECT_FALSE(m.probe_pending());
}

TEST(ProbeMove, TheElementBeforeAProbeEndsAtRestAndTheInputIsCheckedThere) {
  MotionInterpolator m = configured();
  ASSERT_EQ(m.push(line_to({5.0, 0.0}, 20.0)), SegmentRefusal::none);
  ASSERT_EQ(m.push(probe_to(ProbeKind::toward, {5.0, 5.0}, kFeed_mm_s)), SegmentRefusal::none);
  double max_y_before_x_end = 0.0;
  for (long k = 0; k < 100'000 && m.probe_outcome() == ProbeOutcome::none; ++k) {
    m.set_probe_input(false);
    const MotionReference r = m.tick();
    if (r.axis[0].next_position_mm < 5.0) max_y_before_x_end = std::max(max_y_before_x_end, r.axis[1].next_position_mm);
  }
  EXPECT_EQ(max_y_before_x_end, 0.0) << "the corner into the probe was rounded";
  EXPECT_EQ(m.probe_outcome(), ProbeOutcome::not_tripped);
}

TEST(ProbeMove, EachKindEndsAsItDemandsWithoutATrip) {
  struct Case {
    ProbeKind kind;
    bool input;  // constant: never the tripping state
    ProbeOutcome outcome;
  };
  for (const Case c : {Case{ProbeKind::toward_or_error, false, ProbeOutcome::failed},
                       Case{ProbeKind::toward, false, ProbeOutcome::not_tripped},
                       Case{ProbeKind::away_or_error, true, ProbeOutcome::failed},
                       Case{ProbeKind::away, true, ProbeOutcome::not_tripped}}) {
    SCOPED_TRACE(static_cast<int>(c.kind));
    MotionInterpolator m = configured();
    ASSERT_EQ(m.push(probe_to(c.kind, {10.0, 0.0}, kFeed_mm_s)), SegmentRefusal::none);
    const ProbeRunResult r = run_until_outcome(m, [&c](double) { return c.input; });
    EXPECT_EQ(r.outcome, c.outcome);
    EXPECT_EQ(r.trip_tick, -1);
    EXPECT_TRUE(m.at_rest());
    EXPECT_NEAR(m.reference_mm()[0], 10.0, 1e-9) << "decided at rest at the end";
    if (is_error(c.outcome)) {
      // The program stops: nothing after it runs.
      for (int k = 0; k < 100 && m.state() != MotionState::idle; ++k) m.tick();
      EXPECT_EQ(m.state(), MotionState::idle) << "the program did not end";
    } else {
      EXPECT_EQ(m.state(), MotionState::starved) << "the program goes on";
      EXPECT_EQ(m.push(line_to({0.0, 0.0}, 20.0)), SegmentRefusal::none);
    }
  }
}

TEST(ProbeMove, AwayKindsTripWhenContactIsLost) {
  for (const ProbeKind kind : {ProbeKind::away_or_error, ProbeKind::away}) {
    MotionInterpolator m = configured();
    ASSERT_EQ(m.push(probe_to(kind, {10.0, 0.0}, kFeed_mm_s)), SegmentRefusal::none);
    const ProbeRunResult r = run_until_outcome(m, [](double x) { return x < kContact_mm; });
    EXPECT_EQ(r.outcome, ProbeOutcome::tripped);
    EXPECT_GE(r.trip_reference_x_mm, kContact_mm);
    EXPECT_LT(m.reference_mm()[0], 10.0 - 1.0);
  }
}

TEST(ProbeMove, RefusedWhenTheInputAlreadyIsInTheTrippingStateAndTheProgramStops) {
  for (const ProbeKind kind :
       {ProbeKind::toward_or_error, ProbeKind::toward, ProbeKind::away_or_error, ProbeKind::away}) {
    SCOPED_TRACE(static_cast<int>(kind));
    MotionInterpolator m = configured();
    ASSERT_EQ(m.push(probe_to(kind, {10.0, 0.0}, kFeed_mm_s)), SegmentRefusal::none);
    const bool tripping = probe_trips_on(kind, true);  // toward: touching; away: not touching
    const ProbeRunResult r = run_until_outcome(m, [tripping](double) { return tripping; });
    EXPECT_EQ(r.outcome, ProbeOutcome::already_tripped);
    EXPECT_EQ(r.max_x_mm, 0.0) << "it moved";
    for (int k = 0; k < 100 && m.state() != MotionState::idle; ++k) m.tick();
    EXPECT_EQ(m.state(), MotionState::idle) << "the program did not end";
    EXPECT_EQ(m.queued(), 0u);
    EXPECT_FALSE(m.probe_pending());
  }
}

}  // namespace
}  // namespace tnv::fw::motion
