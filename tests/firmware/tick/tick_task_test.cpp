#include "firmware/tick/tick_task.hpp"

#include <gtest/gtest.h>

#include "tests/firmware/fake_io_board.hpp"
#include "tests/firmware/test_units.hpp"

namespace tnv::fw {
namespace {

using test_units::kCountMm;

class TickTaskTest : public ::testing::Test {
 protected:
  TickTaskTest() : task(board, make_config()) {}

  static FirmwareConfig make_config() {
    FirmwareConfig c = default_firmware_config();
    c.axis[0].home_position_mm = 6.0;
    c.axis[1].home_position_mm = 0.0;
    return c;
  }

  void tick(std::uint32_t period = 10'000) {
    board.next_tick(period);
    task.tick();
  }

  tnv::test::FakeIoBoard board;
  TickTask task;
};

TEST_F(TickTaskTest, OneBatchedReadAndWriteAndOneKickPerTick) {
  for (int i = 0; i < 10; ++i) tick();
  EXPECT_EQ(board.reads, 10);
  EXPECT_EQ(board.writes, 10);
  EXPECT_EQ(board.kicks, 10);
}

TEST_F(TickTaskTest, ServoOffOutputsAreMidScaleAndDisabled) {
  tick();
  EXPECT_EQ(task.state(), MotionState::disabled);
  EXPECT_EQ(board.written_code[0], 2048);
  EXPECT_FALSE(board.written_enable[0]);
  EXPECT_FALSE(board.written_enable[1]);
}

TEST_F(TickTaskTest, PositionIsHomePlusCountsAndSpeedUsesTheMeasuredPeriod) {
  board.counts = {1000, 50000};
  tick();
  board.counts = {1048, 50000 - 24};
  tick(12'000);
  const TickRecord& r = task.last_record();
  EXPECT_NEAR(r.axis[0].position_mm, 6.0 + 48 * kCountMm, 1e-12);
  EXPECT_NEAR(r.axis[1].position_mm, -24 * kCountMm, 1e-12);
  EXPECT_NEAR(r.axis[0].speed_mm_s, 48 * kCountMm / 1.2e-3, 1e-9);
  EXPECT_EQ(r.period_clocks, 12'000u);
  EXPECT_EQ(task.counters().late_ticks, 1u);
}

TEST_F(TickTaskTest, StartCircleEnablesServosAndDwellsAtTheStart) {
  tick();
  ASSERT_EQ(task.start_circle(CircleSpec{}), CommandStatus::ok);
  tick();
  EXPECT_EQ(task.state(), MotionState::dwell);
  EXPECT_TRUE(board.written_enable[0]);
  EXPECT_TRUE(board.written_enable[1]);
  EXPECT_NEAR(task.last_record().axis[0].reference_mm, 6.0, 1e-12);
  EXPECT_EQ(task.start_circle(CircleSpec{}), CommandStatus::busy) << "no second start while running";
  EXPECT_EQ(task.select_controller(hal::Axis::x, ControllerKind::pid), CommandStatus::busy);
}

TEST_F(TickTaskTest, StartCircleRefusesBadSpecsAndAFarAwayTable) {
  tick();
  EXPECT_EQ(task.start_circle(CircleSpec{.feed_mm_s = -2.0}), CommandStatus::invalid);
  EXPECT_EQ(task.start_circle(CircleSpec{.radius_mm = 7.0}), CommandStatus::invalid) << "table is at (6, 0)";
  EXPECT_EQ(task.state(), MotionState::disabled) << "a refused command changes nothing";
}

TEST_F(TickTaskTest, FollowingErrorTripZeroesDacAndDropsEnablesWithinTheSameTick) {
  tick();
  ASSERT_EQ(task.start_circle(CircleSpec{}), CommandStatus::ok);
  for (int i = 0; i < 5; ++i) tick();
  ASSERT_TRUE(board.written_enable[0]);
  // The table is dragged 0.1 mm away over 4 ticks (beyond the 0.05 mm floor
  // at rest, 25 mm/s: a step the axis can make, below the speed limit, so
  // following error is the reason; 0.1 mm in one tick is
  // encoder_implausible, TickTaskTest.AnImplausibleCountStepLatchesInItsTick).
  for (int i = 0; i < 4 && task.state() != MotionState::faulted; ++i) {
    board.counts[0] += static_cast<std::uint32_t>(0.025 / kCountMm);
    tick();
  }
  EXPECT_EQ(task.state(), MotionState::faulted);
  EXPECT_EQ(task.fault().reason, FaultReason::following_error);
  EXPECT_EQ(task.fault().axis, 0);
  EXPECT_EQ(task.fault().tick, task.counters().ticks) << "latched in this tick";
  EXPECT_EQ(board.written_code[0], 2048) << "DAC at zero volts in the tick that found the fault";
  EXPECT_EQ(board.written_code[1], 2048);
  EXPECT_FALSE(board.written_enable[0]);
  EXPECT_FALSE(board.written_enable[1]);
  // Latched: stays safe, refuses motion, clears on command once the cause is gone.
  tick();
  EXPECT_EQ(task.state(), MotionState::faulted);
  EXPECT_EQ(task.start_circle(CircleSpec{}), CommandStatus::faulted);
  EXPECT_EQ(task.clear_fault(), CommandStatus::ok);
  tick();
  EXPECT_EQ(task.state(), MotionState::disabled);
  EXPECT_FALSE(task.fault().active());
}

TEST_F(TickTaskTest, AnImplausibleCountStepLatchesInItsTick) {
  tick();
  ASSERT_EQ(task.start_circle(CircleSpec{}), CommandStatus::ok);
  for (int i = 0; i < 5; ++i) tick();
  board.counts[0] += static_cast<std::uint32_t>(0.1 / kCountMm);  // 100 mm/s for one tick from rest
  tick();
  EXPECT_EQ(task.state(), MotionState::faulted);
  EXPECT_EQ(task.fault().reason, FaultReason::encoder_implausible);
  EXPECT_EQ(task.fault().axis, 0);
  EXPECT_EQ(task.fault().tick, task.counters().ticks) << "latched in this tick";
  EXPECT_GT(task.fault().value, task.fault().limit) << "mm off the prediction vs the reachable spread";
  EXPECT_EQ(board.written_code[0], 2048);
  EXPECT_FALSE(board.written_enable[0]);
}

TEST_F(TickTaskTest, ASequenceGoingBackwardsIsStaleAndCountsNothing) {
  for (int i = 0; i < 3; ++i) tick();
  const std::uint64_t missed_before = task.counters().missed_ticks;
  board.latch.sequence -= 2;  // the next tick reads one below the last
  tick();
  EXPECT_EQ(task.state(), MotionState::faulted);
  EXPECT_EQ(task.fault().reason, FaultReason::stale_snapshot);
  EXPECT_EQ(task.counters().missed_ticks, missed_before) << "no 4,294,967,295 lost ticks";
}

TEST_F(TickTaskTest, EstopFaultCannotBeClearedWhileAsserted) {
  tick();
  board.in.estop = true;
  tick();
  EXPECT_EQ(task.fault().reason, FaultReason::estop);
  EXPECT_EQ(task.clear_fault(), CommandStatus::cause_present);
  board.in.estop = false;
  tick();
  EXPECT_EQ(task.clear_fault(), CommandStatus::ok);
}

TEST_F(TickTaskTest, ABoardLatchedEncoderErrorIsResetByTheFirstClearAndClearedByTheNext) {
  tick();
  board.in.encoder_error[1] = true;  // sticky on the board until reset
  tick();
  EXPECT_EQ(task.fault().reason, FaultReason::encoder_error);
  tick();
  EXPECT_EQ(board.latch_clears, 0) << "the tick never resets the board";
  EXPECT_EQ(task.clear_fault(), CommandStatus::cause_present) << "the last snapshot still shows the latch";
  EXPECT_EQ(board.latch_clears, 1);
  tick();
  EXPECT_EQ(task.state(), MotionState::faulted) << "still latched in the firmware";
  EXPECT_EQ(task.clear_fault(), CommandStatus::ok) << "the new snapshot shows the latch gone";
  EXPECT_EQ(board.latch_clears, 1);
  tick();
  EXPECT_EQ(task.state(), MotionState::disabled);
}

TEST_F(TickTaskTest, AnEstopClearDoesNotTouchTheBoardLatches) {
  tick();
  board.in.estop = true;
  tick();
  EXPECT_EQ(task.clear_fault(), CommandStatus::cause_present);
  EXPECT_EQ(board.latch_clears, 0);
}

TEST_F(TickTaskTest, StaleSnapshotIsAFaultNotASilentReuse) {
  tick();
  ASSERT_EQ(task.start_circle(CircleSpec{}), CommandStatus::ok);
  tick();
  task.tick();  // the board did not tick: same sequence, same clock
  EXPECT_EQ(task.fault().reason, FaultReason::stale_snapshot);
  EXPECT_FALSE(board.written_enable[0]);
}

TEST_F(TickTaskTest, MissedTicksAreCountedAndTooManyFault) {
  tick();
  board.latch.sequence += 1;  // one board tick lost
  board.latch.clock_10mhz += 10'000;
  tick();
  EXPECT_EQ(task.counters().missed_ticks, 1u);
  EXPECT_FALSE(task.fault().active());
  board.latch.sequence += 5;
  board.latch.clock_10mhz += 50'000;
  tick();
  EXPECT_EQ(task.fault().reason, FaultReason::missed_ticks);
}

TEST_F(TickTaskTest, BusErrorsFault) {
  tick();
  board.read_status = hal::HalStatus::bus_error;
  tick();
  EXPECT_EQ(task.fault().reason, FaultReason::bus_error);
  EXPECT_EQ(task.counters().bus_errors, 1u);
}

}  // namespace
}  // namespace tnv::fw
