// A feed per revolution (G95, Segment::feed_mm_rev) in the tick, judged on
// the emulated machine: the table's real speed follows the spindle's real
// speed times the feed per revolution, not the commanded speed, and a
// spindle that stops stops the feed (it waits at rest on the path) until it
// turns again.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "emulator/scenario_file.hpp"
#include "tests/hil/hil_rig.hpp"

namespace tnv::hil {
namespace {

namespace motion = fw::motion;

constexpr double kRpm = 3000.0;
constexpr double kFeedMmRev = 0.2;  // 10 mm/s at 3000 rpm

// Held, at rest. A drive gain below the reference plant's (K_sp 10,000 rpm at
// full scale instead of 12,000) makes the spindle turn at 5/6 of its command,
// as one drooping under load; the firmware's at-speed window is widened to
// 25 % so that it counts as at speed.
std::unique_ptr<::tnv::test::HilRig> holding_rig(double drive_rpm_at_full_scale) {
  emu::Scenario s = *emu::builtin_scenario("no-cut");
  s.spindle.rpm_at_full_scale = drive_rpm_at_full_scale;
  fw::FirmwareConfig c = fw::default_firmware_config();
  c.spindle.at_speed_fraction = 0.25;
  auto rig = std::make_unique<::tnv::test::HilRig>(s, c);
  if (!rig->init_ok) return nullptr;
  for (int i = 0; i < 3; ++i) rig->tick();
  if (rig->task.hold_position() != fw::CommandStatus::ok) return nullptr;
  for (int i = 0; i < 10; ++i) rig->tick();
  return rig;
}

// A line along X by dx at kFeedMmRev, its feed_mm_s the speed at the commanded kRpm.
void push_per_rev_line(::tnv::test::HilRig& rig, double dx_mm) {
  motion::PlanePoint end = rig.task.next_segment_start_mm();
  end[0] += dx_mm;
  motion::Segment s = motion::line_to(end, kFeedMmRev * kRpm / 60.0);
  s.feed_mm_rev = kFeedMmRev;
  motion::SegmentRefusal why{};
  ASSERT_EQ(rig.task.push_segment(s, why), fw::CommandStatus::ok) << motion::to_string(why);
}

double table_x_mm(const ::tnv::test::HilRig& rig) { return rig.machine.truth(hal::Axis::x).position_mm; }

TEST(PerRevFeedTick, TheTableFollowsTheSpindlesRealSpeedNotItsCommand) {
  auto rig = holding_rig(10'000.0);
  ASSERT_TRUE(rig);
  ASSERT_EQ(rig->task.spindle_start(fw::SpindleDirection::forward, kRpm), fw::SpindleResult::ok);
  push_per_rev_line(*rig, 40.0);
  ASSERT_EQ(rig->task.end_program(), fw::CommandStatus::ok);
  const double x0 = table_x_mm(*rig);
  int t = 0;
  for (; t < 20'000 && table_x_mm(*rig) < x0 + 10.0; ++t) rig->tick();
  ASSERT_LT(t, 20'000) << "the feed never ran";
  // Mid-line over 1 s: the table's travel against the spindle's real revolutions.
  const double rev0 = rig->machine.spindle_truth().revolutions;
  const double xa = table_x_mm(*rig);
  for (int k = 0; k < 1000; ++k) rig->tick();
  const double turned = rig->machine.spindle_truth().revolutions - rev0;
  const double travel = table_x_mm(*rig) - xa;
  EXPECT_NEAR(turned, 2500.0 / 60.0, 0.01 * 2500.0 / 60.0) << "the spindle turns at 5/6 of its command";
  EXPECT_NEAR(travel / turned, kFeedMmRev, 0.005 * kFeedMmRev) << "mm per real revolution";
  EXPECT_LT(travel, 0.9 * kFeedMmRev * kRpm / 60.0) << "not the commanded speed's 10 mm/s";
}

TEST(PerRevFeedTick, ASpindleThatStopsStopsTheFeedUntilItTurnsAgain) {
  auto rig = holding_rig(12'000.0);
  ASSERT_TRUE(rig);
  ASSERT_EQ(rig->task.spindle_start(fw::SpindleDirection::forward, kRpm), fw::SpindleResult::ok);
  push_per_rev_line(*rig, 20.0);
  ASSERT_EQ(rig->task.end_program(), fw::CommandStatus::ok);
  const double x0 = table_x_mm(*rig);
  int t = 0;
  for (; t < 20'000 && table_x_mm(*rig) < x0 + 5.0; ++t) rig->tick();
  ASSERT_LT(t, 20'000) << "the feed never ran";
  rig->task.spindle_stop();
  for (int k = 0; k < 500; ++k) rig->tick();  // braking on the path
  const double x_stopped = table_x_mm(*rig);
  EXPECT_LT(x_stopped, x0 + 15.0) << "it ran on at its speed";
  // The spindle runs down over about a second; the table stays where it stopped all that time.
  for (int k = 0; k < 3000; ++k) {
    rig->tick();
    ASSERT_NEAR(table_x_mm(*rig), x_stopped, 0.002) << "the table moved " << k << " ticks after the stop, spindle at "
                                                   << rig->machine.spindle_truth().speed_rpm << " rpm";
  }
  EXPECT_LT(std::fabs(rig->machine.spindle_truth().speed_rpm), 1.0);
  EXPECT_EQ(rig->task.motion().state(), motion::MotionState::running) << "the program waits, it did not end";
  // Turning again (and at speed): the line goes on to its end.
  ASSERT_EQ(rig->task.spindle_start(fw::SpindleDirection::forward, kRpm), fw::SpindleResult::ok);
  for (int k = 0; k < 20'000 && table_x_mm(*rig) < x0 + 19.99; ++k) rig->tick();
  EXPECT_NEAR(table_x_mm(*rig), x0 + 20.0, 0.01);
}

}  // namespace
}  // namespace tnv::hil
