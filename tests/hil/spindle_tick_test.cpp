// The spindle in the tick (issue 27), judged on the emulated machine: the
// spindle's real speed (SpindleDrive) and the table's real motion, not the
// firmware's own view. Feed moves wait for at-speed; a spindle that is off
// blocks nothing; the spindle stops at a program's end, on abort, e-stop,
// fault and host loss, and turns again only on a new start.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "emulator/scenario_file.hpp"
#include "tests/hil/hil_rig.hpp"

namespace tnv::hil {
namespace {

namespace motion = fw::motion;

constexpr double kRpm = 3000.0;
constexpr double kMovingMmS = 0.05;  // the table counts as moving above this (real speed)

bool table_moving(const ::tnv::test::HilRig& rig) {
  return std::fabs(rig.machine.truth(hal::Axis::x).speed_mm_s) > kMovingMmS ||
         std::fabs(rig.machine.truth(hal::Axis::y).speed_mm_s) > kMovingMmS;
}
// The spindle really turns within the firmware's default at-speed window of `rpm`.
bool really_at_speed(const ::tnv::test::HilRig& rig, double rpm) {
  return std::fabs(rig.machine.spindle_truth().speed_rpm - rpm) <= std::max(0.05 * std::fabs(rpm), 20.0);
}
double spindle_rpm(const ::tnv::test::HilRig& rig) { return rig.machine.spindle_truth().speed_rpm; }

std::unique_ptr<::tnv::test::HilRig> holding_rig() {
  auto rig = std::make_unique<::tnv::test::HilRig>(*emu::builtin_scenario("no-cut"));
  if (!rig->init_ok) return nullptr;
  for (int i = 0; i < 3; ++i) rig->tick();
  if (rig->task.hold_position() != fw::CommandStatus::ok) return nullptr;
  for (int i = 0; i < 10; ++i) rig->tick();
  return rig;
}

motion::Segment line_by(const ::tnv::test::HilRig& rig, double dx_mm, double feed_mm_s, bool rapid = false) {
  motion::PlanePoint end = rig.task.next_segment_start_mm();
  end[0] += dx_mm;
  motion::Segment s = motion::line_to(end, feed_mm_s);
  s.rapid = rapid;
  return s;
}

void push(::tnv::test::HilRig& rig, const motion::Segment& s) {
  motion::SegmentRefusal why{};
  ASSERT_EQ(rig.task.push_segment(s, why), fw::CommandStatus::ok) << motion::to_string(why);
}

// Ticks until the table moves (or `limit`); the tick count it took.
int ticks_until_moving(::tnv::test::HilRig& rig, int limit) {
  for (int t = 1; t <= limit; ++t) {
    rig.tick();
    if (table_moving(rig)) return t;
  }
  return -1;
}

void run(::tnv::test::HilRig& rig, int ticks) {
  for (int i = 0; i < ticks; ++i) rig.tick();
}

// A line, a program pause and a line, the program closed: true once the
// motion core waits at the pause (within 10 s).
bool run_to_a_pause(::tnv::test::HilRig& rig) {
  push(rig, line_by(rig, 2.0, 10.0));
  push(rig, motion::pause_here());
  push(rig, line_by(rig, 2.0, 10.0));
  if (rig.task.end_program() != fw::CommandStatus::ok) return false;
  for (int t = 0; t < 10000 && rig.task.motion().state() != motion::MotionState::paused; ++t) rig.tick();
  return rig.task.motion().state() == motion::MotionState::paused;
}

TEST(SpindleTick, AFeedMoveStartsOnlyOnceTheSpindleIsReallyAtSpeed) {
  auto rig = holding_rig();
  ASSERT_TRUE(rig);
  ASSERT_EQ(rig->task.spindle_start(fw::SpindleDirection::forward, kRpm), fw::SpindleResult::ok);
  push(*rig, line_by(*rig, 3.0, 10.0));
  ASSERT_EQ(rig->task.end_program(), fw::CommandStatus::ok);
  const int onset = ticks_until_moving(*rig, 5000);
  ASSERT_GT(onset, 0) << "the feed move never started";
  // The ramp alone (3000 rpm at 5000 rpm/s) takes 600 ticks.
  EXPECT_GT(onset, 600);
  EXPECT_TRUE(really_at_speed(*rig, kRpm)) << "the table moved with the spindle at " << spindle_rpm(*rig) << " rpm";
  EXPECT_TRUE(rig->task.last_record().spindle.enabled);
}

TEST(SpindleTick, ARapidRunsWhileTheSpindleRampsAndTheFeedMoveAfterItWaits) {
  auto rig = holding_rig();
  ASSERT_TRUE(rig);
  const double x0 = rig->machine.truth(hal::Axis::x).position_mm;
  ASSERT_EQ(rig->task.spindle_start(fw::SpindleDirection::forward, kRpm), fw::SpindleResult::ok);
  push(*rig, line_by(*rig, 2.0, 20.0, true));
  push(*rig, line_by(*rig, 2.0, 10.0));
  ASSERT_EQ(rig->task.end_program(), fw::CommandStatus::ok);
  const int onset = ticks_until_moving(*rig, 200);
  ASSERT_GT(onset, 0) << "the rapid waited for the spindle";
  EXPECT_LT(std::fabs(spindle_rpm(*rig)), 0.5 * kRpm) << "the rapid should run while the spindle ramps";
  // Past the rapid's end by more than the loop's error: only with the spindle at speed.
  bool beyond = false;
  for (int t = 0; t < 5000 && !beyond; ++t) {
    rig->tick();
    if (rig->machine.truth(hal::Axis::x).position_mm > x0 + 2.01) {
      beyond = true;
      EXPECT_TRUE(really_at_speed(*rig, kRpm)) << "the feed move began at " << spindle_rpm(*rig) << " rpm";
    }
  }
  EXPECT_TRUE(beyond) << "the feed move never ran";
}

TEST(SpindleTick, ASpindleThatIsOffBlocksNothingAndStaysOff) {
  auto rig = holding_rig();
  ASSERT_TRUE(rig);
  push(*rig, line_by(*rig, 3.0, 10.0));
  ASSERT_EQ(rig->task.end_program(), fw::CommandStatus::ok);
  const int onset = ticks_until_moving(*rig, 200);
  ASSERT_GT(onset, 0);
  EXPECT_LT(onset, 100);
  run(*rig, 1500);
  EXPECT_EQ(rig->task.state(), fw::MotionState::holding) << "the program should have ended";
  EXPECT_EQ(spindle_rpm(*rig), 0.0);
  EXPECT_FALSE(rig->machine.board_outputs().spindle_enabled);
}

TEST(SpindleTick, TheProgramsEndStopsTheSpindle) {
  auto rig = holding_rig();
  ASSERT_TRUE(rig);
  ASSERT_EQ(rig->task.spindle_start(fw::SpindleDirection::reverse, kRpm), fw::SpindleResult::ok);
  run(*rig, 1500);
  EXPECT_TRUE(really_at_speed(*rig, -kRpm)) << spindle_rpm(*rig);
  EXPECT_TRUE(rig->task.last_record().spindle.reverse);
  push(*rig, line_by(*rig, 1.0, 10.0));
  ASSERT_EQ(rig->task.end_program(), fw::CommandStatus::ok);
  run(*rig, 500);
  EXPECT_EQ(rig->task.state(), fw::MotionState::holding);
  EXPECT_FALSE(rig->task.spindle().commanded_on());
  EXPECT_EQ(rig->task.spindle().last_stop_cause(), fw::SpindleStopCause::program_end);
  run(*rig, 2500);
  EXPECT_LT(std::fabs(spindle_rpm(*rig)), 1.0);
  EXPECT_FALSE(rig->machine.board_outputs().spindle_enabled) << "the controlled stop ends with the enable dropped";
}

TEST(SpindleTick, AnAbortedProgramStopsTheSpindleAndLeavesItStopped) {
  auto rig = holding_rig();
  ASSERT_TRUE(rig);
  ASSERT_EQ(rig->task.spindle_start(fw::SpindleDirection::forward, kRpm), fw::SpindleResult::ok);
  push(*rig, line_by(*rig, 10.0, 5.0));
  ASSERT_GT(ticks_until_moving(*rig, 5000), 0);
  ASSERT_EQ(rig->task.stop(), fw::CommandStatus::ok);
  EXPECT_EQ(rig->task.spindle().last_stop_cause(), fw::SpindleStopCause::abort);
  run(*rig, 3000);
  EXPECT_EQ(rig->task.state(), fw::MotionState::holding);
  EXPECT_LT(std::fabs(spindle_rpm(*rig)), 1.0);
  // A new program with the spindle off runs at once and does not start it.
  push(*rig, line_by(*rig, 1.0, 10.0));
  ASSERT_EQ(rig->task.end_program(), fw::CommandStatus::ok);
  EXPECT_GT(ticks_until_moving(*rig, 200), 0);
  run(*rig, 1000);
  EXPECT_LT(std::fabs(spindle_rpm(*rig)), 1.0);
}

TEST(SpindleTick, AfterAnEstopReleaseTheSpindleTurnsOnlyOnANewStart) {
  auto rig = holding_rig();
  ASSERT_TRUE(rig);
  ASSERT_EQ(rig->task.spindle_start(fw::SpindleDirection::forward, kRpm), fw::SpindleResult::ok);
  run(*rig, 1500);
  ASSERT_TRUE(really_at_speed(*rig, kRpm));
  rig->machine.set_estop(true);
  rig->tick();
  EXPECT_FALSE(rig->machine.board_outputs().spindle_enabled) << "the e-stop drops the spindle's enable in its tick";
  EXPECT_EQ(rig->task.spindle().last_stop_cause(), fw::SpindleStopCause::estop);
  EXPECT_EQ(rig->task.spindle_start(fw::SpindleDirection::forward, kRpm), fw::SpindleResult::inhibited);
  run(*rig, 3000);
  rig->machine.set_estop(false);
  rig->tick();
  ASSERT_EQ(rig->task.clear_fault(), fw::CommandStatus::ok);
  ASSERT_EQ(rig->task.hold_position(), fw::CommandStatus::ok);
  double peak = 0.0;
  for (int i = 0; i < 3000; ++i) {
    rig->tick();
    peak = std::max(peak, std::fabs(spindle_rpm(*rig)));
  }
  EXPECT_LT(peak, 1.0) << "the spindle turned after the e-stop release without a start";
  EXPECT_FALSE(rig->machine.board_outputs().spindle_enabled);
  ASSERT_EQ(rig->task.spindle_start(fw::SpindleDirection::forward, kRpm), fw::SpindleResult::ok);
  run(*rig, 1500);
  EXPECT_TRUE(really_at_speed(*rig, kRpm));
}

TEST(SpindleTick, AFaultStopsTheSpindleAndClearingItDoesNotStartIt) {
  auto rig = holding_rig();
  ASSERT_TRUE(rig);
  ASSERT_EQ(rig->task.spindle_start(fw::SpindleDirection::forward, kRpm), fw::SpindleResult::ok);
  run(*rig, 1500);
  rig->machine.set_servo_alarm(hal::Axis::y, true);
  rig->tick();
  ASSERT_EQ(rig->task.state(), fw::MotionState::faulted);
  EXPECT_EQ(rig->task.spindle().last_stop_cause(), fw::SpindleStopCause::fault);
  EXPECT_FALSE(rig->machine.board_outputs().spindle_enabled);
  rig->machine.set_servo_alarm(hal::Axis::y, false);
  run(*rig, 2);
  ASSERT_EQ(rig->task.clear_fault(), fw::CommandStatus::ok);
  double peak_after = 0.0;
  run(*rig, 3000);  // coasting down
  for (int i = 0; i < 1000; ++i) {
    rig->tick();
    peak_after = std::max(peak_after, std::fabs(spindle_rpm(*rig)));
  }
  EXPECT_LT(peak_after, 1.0);
}

TEST(SpindleTick, AHostLossStopsTheSpindleAndItsReturnDoesNotStartIt) {
  auto rig = holding_rig();
  ASSERT_TRUE(rig);
  ASSERT_EQ(rig->task.spindle_start(fw::SpindleDirection::forward, kRpm), fw::SpindleResult::ok);
  run(*rig, 1500);
  rig->task.set_host_lost(true);
  EXPECT_FALSE(rig->task.spindle().commanded_on());
  EXPECT_EQ(rig->task.spindle().last_stop_cause(), fw::SpindleStopCause::host_timeout);
  EXPECT_EQ(rig->task.spindle_start(fw::SpindleDirection::forward, kRpm), fw::SpindleResult::inhibited);
  run(*rig, 3000);
  rig->task.set_host_lost(false);
  run(*rig, 1000);
  EXPECT_LT(std::fabs(spindle_rpm(*rig)), 1.0);
  EXPECT_EQ(rig->task.spindle_start(fw::SpindleDirection::forward, kRpm), fw::SpindleResult::ok);
}

TEST(SpindleTick, ParametersChangeOnlyWhileTheSpindleIsStoppedAndStill) {
  auto rig = holding_rig();
  ASSERT_TRUE(rig);
  fw::FirmwareConfig next = rig->task.config();
  next.spindle.accel_rpm_s = 2000.0;
  ASSERT_EQ(rig->task.spindle_start(fw::SpindleDirection::forward, kRpm), fw::SpindleResult::ok);
  run(*rig, 1500);
  EXPECT_EQ(rig->task.apply_config(next), fw::CommandStatus::spindle_running);
  EXPECT_EQ(rig->task.spindle().params().accel_rpm_s, fw::SpindleParams{}.accel_rpm_s) << "a refusal changes nothing";
  EXPECT_EQ(rig->task.config().spindle.accel_rpm_s, fw::SpindleParams{}.accel_rpm_s);
  rig->task.spindle_stop();
  run(*rig, 50);
  EXPECT_EQ(rig->task.apply_config(next), fw::CommandStatus::spindle_running) << "still turning down";
  run(*rig, 4000);
  EXPECT_EQ(rig->task.apply_config(next), fw::CommandStatus::ok);
  EXPECT_EQ(rig->task.spindle().params().accel_rpm_s, 2000.0);
  EXPECT_FALSE(rig->task.spindle().commanded_on()) << "a parameter change never starts it";
}

TEST(SpindleTick, AProgramPauseLeavesTheSpindleTurning) {
  auto rig = holding_rig();
  ASSERT_TRUE(rig);
  ASSERT_EQ(rig->task.spindle_start(fw::SpindleDirection::forward, kRpm), fw::SpindleResult::ok);
  ASSERT_TRUE(run_to_a_pause(*rig));
  run(*rig, 2000);
  EXPECT_TRUE(rig->task.spindle().commanded_on()) << "M0/M1/M6 do not stop the spindle";
  EXPECT_TRUE(really_at_speed(*rig, kRpm)) << spindle_rpm(*rig) << " rpm";
  EXPECT_FALSE(table_moving(*rig));
  ASSERT_EQ(rig->task.cycle_start(), fw::CommandStatus::ok);
  ASSERT_GT(ticks_until_moving(*rig, 50), 0) << "at speed: the feed after the pause starts at once";
}

TEST(SpindleTick, AfterAPauseWithTheSpindleRestartedTheFeedWaitsForAtSpeed) {
  auto rig = holding_rig();
  ASSERT_TRUE(rig);
  ASSERT_TRUE(run_to_a_pause(*rig));
  run(*rig, 500);  // the reference rests from the pause's first tick; the table settles behind it
  ASSERT_FALSE(table_moving(*rig));
  // During the pause (a manual tool change, say) the operator starts the spindle, and continues at once.
  ASSERT_EQ(rig->task.spindle_start(fw::SpindleDirection::forward, kRpm), fw::SpindleResult::ok);
  ASSERT_EQ(rig->task.cycle_start(), fw::CommandStatus::ok);
  const int onset = ticks_until_moving(*rig, 5000);
  ASSERT_GT(onset, 0) << "the feed move never started";
  EXPECT_GT(onset, 600) << "the ramp alone takes 600 ticks";
  EXPECT_TRUE(really_at_speed(*rig, kRpm)) << "the table moved with the spindle at " << spindle_rpm(*rig) << " rpm";
}

// S / M3 / M5 in the program (Segment::spindle): the start is carried out
// only when the table rests where the program puts it, the feed after it
// waits for at-speed, and the stop stops it before the next move.
TEST(SpindleTick, AProgramsSpindleCommandsRunInProgramOrderAtRest) {
  auto rig = holding_rig();
  ASSERT_TRUE(rig);
  const double x0 = rig->task.next_segment_start_mm()[0];
  push(*rig, line_by(*rig, 2.0, 20.0, true));  // a rapid
  push(*rig, motion::spindle_here(motion::SpindleChange::forward, kRpm));
  push(*rig, line_by(*rig, 2.0, 10.0));
  push(*rig, motion::spindle_here(motion::SpindleChange::stop, 0.0));
  push(*rig, line_by(*rig, 2.0, 10.0));
  ASSERT_EQ(rig->task.end_program(), fw::CommandStatus::ok);
  double x_at_start = -1.0;
  double x_at_stop = -1.0;
  bool fed_slow = false;  // the table past the rapid's end with the spindle not at speed
  bool was_on = false;
  for (int t = 0; t < 20000 && rig->task.state() != fw::MotionState::holding; ++t) {
    rig->tick();
    const double ref_x = rig->task.last_record().axis[0].reference_mm;
    const bool on = rig->task.spindle().commanded_on();
    if (on && !was_on) x_at_start = ref_x;
    if (!on && was_on) x_at_stop = ref_x;
    was_on = on;
    const double x = rig->machine.truth(hal::Axis::x).position_mm;
    if (on && x > x0 + 2.01 && x < x0 + 3.99 && !really_at_speed(*rig, kRpm)) fed_slow = true;
  }
  ASSERT_EQ(rig->task.state(), fw::MotionState::holding) << "the program did not end";
  EXPECT_NEAR(x_at_start, x0 + 2.0, 1e-6) << "the start was carried out away from its place in the program";
  EXPECT_NEAR(x_at_stop, x0 + 4.0, 1e-6) << "the stop was carried out away from its place in the program";
  EXPECT_FALSE(fed_slow) << "a feed move ran with the spindle below speed";
  EXPECT_FALSE(rig->task.spindle().commanded_on());
  EXPECT_EQ(rig->task.spindle().last_stop_cause(), fw::SpindleStopCause::command);
  EXPECT_NEAR(rig->task.last_record().axis[0].reference_mm, x0 + 6.0, 1e-6);
}

TEST(SpindleTick, AProgramsSpindleStartAboveMaxRpmIsRefusedWhenPushed) {
  auto rig = holding_rig();
  ASSERT_TRUE(rig);
  push(*rig, line_by(*rig, 2.0, 10.0));
  const std::size_t queued = rig->task.motion().queued();
  motion::SegmentRefusal why{};
  const double too_fast = rig->task.spindle().params().max_rpm * 1.01;
  EXPECT_EQ(rig->task.push_segment(motion::spindle_here(motion::SpindleChange::forward, too_fast), why),
            fw::CommandStatus::invalid);
  EXPECT_EQ(why, motion::SegmentRefusal::bad_spindle);
  EXPECT_EQ(rig->task.motion().queued(), queued) << "the queue changed";
}

TEST(SpindleTick, ASpeedChangeWhileCuttingHoldsTheFeedUntilTheNewSpeed) {
  auto rig = holding_rig();
  ASSERT_TRUE(rig);
  ASSERT_EQ(rig->task.spindle_start(fw::SpindleDirection::forward, kRpm), fw::SpindleResult::ok);
  push(*rig, line_by(*rig, 20.0, 5.0));
  ASSERT_GT(ticks_until_moving(*rig, 5000), 0);
  run(*rig, 200);
  ASSERT_EQ(rig->task.spindle_set_speed(2.0 * kRpm), fw::SpindleResult::ok);
  // The table brakes to rest and moves again only with the spindle at the new speed.
  bool stopped = false;
  int t = 0;
  for (; t < 1000 && !stopped; ++t) {
    rig->tick();
    stopped = !table_moving(*rig);
  }
  ASSERT_TRUE(stopped) << "the feed did not wait for the new speed";
  EXPECT_TRUE(rig->task.last_record().spindle.feed_gate_waiting);
  // While the gate waits the table only settles where it braked (a hard
  // brake leaves the servo a few tenths of a micrometre of ringing, which
  // crosses the 0.05 mm/s speed mark): it does not travel.
  const double held_x = rig->machine.truth(hal::Axis::x).position_mm;
  int waited = 0;
  for (; waited < 5000 && rig->task.last_record().spindle.feed_gate_waiting; ++waited) {
    rig->tick();
    ASSERT_NEAR(rig->machine.truth(hal::Axis::x).position_mm, held_x, 0.002) << "the table travelled while waiting";
  }
  ASSERT_LT(waited, 5000) << "the gate never opened";
  EXPECT_TRUE(really_at_speed(*rig, 2.0 * kRpm)) << "the gate opened at " << spindle_rpm(*rig) << " rpm";
  ASSERT_GT(ticks_until_moving(*rig, 5000), 0);
}

}  // namespace
}  // namespace tnv::hil
