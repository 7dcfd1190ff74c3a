// A feed per revolution in the motion core (Segment::feed_mm_rev, G95):
// the path runs at feed_mm_rev times the spindle speed set for the tick
// (MotionInterpolator::set_spindle_rpm), not at its feed_mm_s (the speed at
// the programmed spindle speed); at 0 rpm it brakes to rest on the path and
// waits; the limits hold throughout. And SpindleSyncedFeed, the speed the
// tick hands it: measured, 0 while not at speed, never one kept from before.
#include <gtest/gtest.h>

#include <cmath>

#include "firmware/motion/spindle_synced_feed.hpp"
#include "tests/firmware/motion/motion_run.hpp"

namespace tnv::fw::motion {
namespace {

using test::configured;
using test::run_program;

Segment per_rev_line(PlanePoint end, double feed_mm_rev, double programmed_rpm) {
  Segment s = line_to(end, feed_mm_rev * programmed_rpm / 60.0);
  s.feed_mm_rev = feed_mm_rev;
  return s;
}

// Path speed (X) over the ticks [from, to) of a run.
double mean_speed_mm_s(const test::MotionRun& run, std::size_t from, std::size_t to, double dt_s) {
  return (run.position_mm[to][0] - run.position_mm[from][0]) / (static_cast<double>(to - from) * dt_s);
}

TEST(PerRevFeed, ThePathRunsAtTheFeedPerRevolutionTimesTheSpindleSpeedItIsGiven) {
  for (const double rpm : {6000.0, 5000.0, 7000.0}) {
    MotionInterpolator m = configured();
    m.set_spindle_rpm(rpm);
    // 0.2 mm/rev programmed at 6000 rpm: 20 mm/s there.
    const test::MotionRun run = run_program(m, {per_rev_line({60.0, 0.0}, 0.2, 6000.0)});
    ASSERT_NEAR(m.reference_mm()[0], 60.0, 1e-9);
    const double dt = m.limits().tick_period_s;
    const std::size_t mid = run.position_mm.size() / 2;
    EXPECT_NEAR(mean_speed_mm_s(run, mid - 200, mid + 200, dt), 0.2 * rpm / 60.0, 1e-6) << rpm << " rpm";
    EXPECT_EQ(m.spindle_feed_factor(), 1.0) << "back to 1 once nothing per revolution is in front";
    EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-9);
    EXPECT_LE(run.jerk_ratio_max, 1.0 + 1e-9);
  }
}

TEST(PerRevFeed, AFeedPerMinuteIgnoresTheSpindleSpeed) {
  MotionInterpolator m = configured();
  m.set_spindle_rpm(3000.0);
  const test::MotionRun run = run_program(m, {line_to({60.0, 0.0}, 20.0)});
  const std::size_t mid = run.position_mm.size() / 2;
  EXPECT_NEAR(mean_speed_mm_s(run, mid - 200, mid + 200, m.limits().tick_period_s), 20.0, 1e-6);
}

TEST(PerRevFeed, ASpindleAtZeroHoldsItAtRestOnThePathAndItGoesOnWhenTheSpindleTurns) {
  MotionInterpolator m = configured();
  m.set_spindle_rpm(0.0);
  ASSERT_EQ(m.push(per_rev_line({20.0, 0.0}, 0.2, 6000.0)), SegmentRefusal::none);
  m.end_program();
  for (int k = 0; k < 500; ++k) ASSERT_EQ(m.tick().axis[0].next_position_mm, 0.0) << "moved at tick " << k;
  // Turning: it runs; stopped mid-line: it brakes to rest on the line within the limits and waits there.
  const test::MotionRun run = run_program(m, {}, 100'000, [](std::size_t k, MotionInterpolator& mi) {
    mi.set_spindle_rpm(k < 400 ? 6000.0 : k < 1900 ? 0.0 : 6000.0);
  });
  std::size_t still = 0;
  for (std::size_t k = 700; k < 1900; ++k)
    if (run.position_mm[k] == run.position_mm[k - 1]) ++still;
  EXPECT_EQ(still, 1200u) << "the path moved while the spindle stood";
  EXPECT_GT(run.position_mm[1000][0], 1.0);
  EXPECT_LT(run.position_mm[1000][0], 19.0);
  EXPECT_EQ(run.position_mm[1000][1], 0.0);
  EXPECT_NEAR(run.position_mm.back()[0], 20.0, 1e-9);
  EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-9);
  EXPECT_LE(run.jerk_ratio_max, 1.0 + 1e-9);
}

TEST(PerRevFeed, OnlyAPlainFeedLineIsFedPerRevolution) {
  MotionInterpolator m = configured();
  Segment rapid = per_rev_line({5.0, 0.0}, 0.1, 6000.0);
  rapid.rapid = true;
  EXPECT_EQ(m.push(rapid), SegmentRefusal::bad_kind);
  Segment arc = arc_to(false, {10.0, 0.0}, {5.0, 0.0}, 10.0);
  arc.feed_mm_rev = 0.1;
  EXPECT_EQ(m.push(arc), SegmentRefusal::bad_kind);
  Segment profiled = per_rev_line({5.0, 0.0}, 0.1, 6000.0);
  profiled.ramp_s = 0.1;
  EXPECT_EQ(m.push(profiled), SegmentRefusal::bad_kind);
  Segment negative = per_rev_line({5.0, 0.0}, 0.1, 6000.0);
  negative.feed_mm_rev = -0.1;
  EXPECT_EQ(m.push(negative), SegmentRefusal::feed_not_positive);
  Segment nan = per_rev_line({5.0, 0.0}, 0.1, 6000.0);
  nan.feed_mm_rev = std::nan("");
  EXPECT_EQ(m.push(nan), SegmentRefusal::not_finite);
  EXPECT_EQ(m.queued(), 0u);
  EXPECT_EQ(m.push(per_rev_line({5.0, 0.0}, 0.1, 6000.0)), SegmentRefusal::none);
}

// Along a boring pass's depth (Segment::overhang_at_end_mm): one Z line from
// the mouth (overhang 40 mm at Z 20) to 250 mm below it; the infeed is the
// schedule's at the path point's overhang every tick, S4 eq. (3)'s power law
// through (40 mm, 0.4 mm/rev) and (310 mm, 0.1 mm/rev), not held over segments.
constexpr InfeedAlongOverhang kSchedule{40.0, 0.4, 310.0, 0.1};

Segment depth_line(double end_z_mm, double overhang_at_end_mm, double programmed_rpm) {
  Segment s = line_to({0.0, 0.0, end_z_mm}, 0.4 * programmed_rpm / 60.0);  // the largest infeed's speed
  s.overhang_at_end_mm = overhang_at_end_mm;
  return s;
}

TEST(PerRevFeed, AlongTheDepthTheInfeedIsTheSchedulesAtTheBarsOverhangEveryTick) {
  for (const double rpm : {6000.0, 4500.0}) {
    MotionInterpolator m = configured({0.0, 0.0, 20.0});
    m.set_spindle_rpm(rpm);
    m.set_depth_infeed(kSchedule);
    const test::MotionRun run = run_program(m, {depth_line(-230.0, 290.0, 6000.0)});
    ASSERT_NEAR(m.reference_mm()[2], -230.0, 1e-9);
    const double dt = m.limits().tick_period_s;
    // Z speed over revolutions per second at depths between the gauge ones, in no segment's middle or end.
    int checked = 0;
    for (const double depth_mm : {23.0, 61.5, 118.0, 177.3, 226.0}) {
      std::size_t k = 1;
      while (k + 1 < run.position_mm.size() && run.position_mm[k][2] > 20.0 - depth_mm) ++k;
      ASSERT_LT(k + 50, run.position_mm.size());
      const double vz = (run.position_mm[k - 20][2] - run.position_mm[k + 20][2]) / (40.0 * dt);
      const double s_mm_rev = vz / (rpm / 60.0);
      const double expected = 0.4 * std::pow((40.0 + depth_mm) / 40.0, std::log(0.25) / std::log(310.0 / 40.0));
      EXPECT_NEAR(s_mm_rev, expected, 0.01 * expected) << depth_mm << " mm deep at " << rpm << " rpm";
      ++checked;
    }
    EXPECT_EQ(checked, 5);
    EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-9);
    EXPECT_LE(run.jerk_ratio_max, 1.0 + 1e-9);
  }
}

TEST(PerRevFeed, AlongTheDepthAStoppedSpindleOrNoScheduleStopsTheFeed) {
  MotionInterpolator m = configured();
  m.set_spindle_rpm(0.0);
  m.set_depth_infeed(kSchedule);
  ASSERT_EQ(m.push(depth_line(-100.0, 140.0, 6000.0)), SegmentRefusal::none);
  m.end_program();
  for (int k = 0; k < 500; ++k) ASSERT_EQ(m.tick().axis[2].next_position_mm, 0.0) << "moved at tick " << k;
  m.set_spindle_rpm(6000.0);
  m.set_depth_infeed({});  // no schedule: no infeed
  for (int k = 0; k < 500; ++k) ASSERT_EQ(m.tick().axis[2].next_position_mm, 0.0) << "moved at tick " << k;
  // With both: it runs to its end; the spindle stopped mid-depth: at rest on the line until it turns again.
  m.set_depth_infeed(kSchedule);
  const test::MotionRun run = run_program(m, {}, 100'000, [](std::size_t k, MotionInterpolator& mi) {
    mi.set_spindle_rpm(k < 1000 ? 6000.0 : k < 2500 ? 0.0 : 6000.0);
  });
  std::size_t still = 0;
  for (std::size_t k = 1500; k < 2500; ++k)
    if (run.position_mm[k] == run.position_mm[k - 1]) ++still;
  EXPECT_EQ(still, 1000u) << "the path moved while the spindle stood";
  EXPECT_LT(run.position_mm[2000][2], -1.0);
  EXPECT_GT(run.position_mm[2000][2], -99.0);
  EXPECT_NEAR(run.position_mm.back()[2], -100.0, 1e-9);
  EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-9);
  EXPECT_LE(run.jerk_ratio_max, 1.0 + 1e-9);
}

TEST(PerRevFeed, AlongTheDepthTheOverhangIsPositiveAndTheOnlyFeedPerRevolution) {
  MotionInterpolator m = configured();
  Segment both = depth_line(-10.0, 50.0, 6000.0);
  both.feed_mm_rev = 0.1;
  EXPECT_EQ(m.push(both), SegmentRefusal::bad_kind);
  Segment negative = depth_line(-10.0, -50.0, 6000.0);
  EXPECT_EQ(m.push(negative), SegmentRefusal::bad_kind);
  Segment nan = depth_line(-10.0, std::nan(""), 6000.0);
  EXPECT_EQ(m.push(nan), SegmentRefusal::not_finite);
  Segment rapid = depth_line(-10.0, 50.0, 6000.0);
  rapid.rapid = true;
  EXPECT_EQ(m.push(rapid), SegmentRefusal::bad_kind);
  EXPECT_EQ(m.queued(), 0u);
  EXPECT_EQ(m.push(depth_line(-10.0, 50.0, 6000.0)), SegmentRefusal::none);
}

TEST(InfeedAlongOverhang, TheLawBetweenTheGaugeOverhangsAndItsEndsOutside) {
  EXPECT_DOUBLE_EQ(kSchedule.at(40.0), 0.4);
  EXPECT_NEAR(kSchedule.at(310.0), 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(kSchedule.at(20.0), 0.4) << "above the top gauge: its infeed";
  EXPECT_NEAR(kSchedule.at(320.0), 0.1, 1e-12) << "below the bottom gauge: its infeed";
  EXPECT_DOUBLE_EQ(kSchedule.at(100.0), infeed_along_overhang_mm_rev(100.0, 40.0, 0.4, 310.0, 0.1));
  EXPECT_TRUE(std::isnan(InfeedAlongOverhang{}.at(100.0)));
  EXPECT_TRUE(std::isnan(kSchedule.at(std::nan(""))));
}

TEST(SpindleSyncedFeed, MeasuredWhileAtSpeedAndZeroOtherwise) {
  SpindleSyncedFeed f;
  EXPECT_EQ(f.tick(false, 6000.0, 1e-3), 0.0) << "not at speed: no feed";
  EXPECT_EQ(f.tick(true, -5900.0, 1e-3), 5900.0) << "at speed: this tick's measurement, either direction";
  // The count's quantisation (+-1 count of 409.6 a period at 6000 rpm) does not move it.
  for (int k = 0; k < 200; ++k) EXPECT_EQ(f.tick(true, k % 2 ? 5900.0 * 1.0024 : 5900.0 * 0.9976, 1e-3), 5900.0);
  // A real change (a droop of 5 %) is followed within tens of ticks.
  double rpm = 0.0;
  for (int k = 0; k < 40; ++k) rpm = f.tick(true, 5605.0, 1e-3);
  EXPECT_NEAR(rpm, 5605.0, 0.0025 * 5605.0);
  // Stopped: 0 at once, and what was measured before is not used again.
  EXPECT_EQ(f.tick(false, 5605.0, 1e-3), 0.0);
  EXPECT_EQ(f.tick(true, 3000.0, 1e-3), 3000.0);
  EXPECT_EQ(f.tick(true, std::nan(""), 1e-3), 0.0) << "no number, no feed";
}

}  // namespace
}  // namespace tnv::fw::motion
