// The TickTask commands the CAN node uses: apply_config (all or nothing,
// busy for what is not live-tunable while moving), stop, zero, estop.
#include <gtest/gtest.h>

#include <limits>

#include "firmware/can/param_table.hpp"
#include "firmware/can/staged_params.hpp"
#include "firmware/tick/tick_task.hpp"
#include "tests/firmware/fake_io_board.hpp"

namespace tnv::fw {
namespace {

const FirmwareConfig& base_config() {
  static const FirmwareConfig c = [] {
    FirmwareConfig f = default_firmware_config();
    f.axis[0].home_position_mm = 6.0;
    return f;
  }();
  return c;
}

struct Bench {
  Bench() : task(board, base_config()) { tick(); }
  void tick(int n = 1) {
    for (int i = 0; i < n; ++i) {
      board.next_tick();
      task.tick();
    }
  }
  test::FakeIoBoard board;
  TickTask task;
};

TEST(TickTaskApplyConfig, AnInvalidConfigChangesNothing) {
  Bench b;
  FirmwareConfig bad = b.task.config();
  bad.axis[0].sliding.gamma = 0.3;
  bad.axis[1].sliding.q = 1.5;  // S1 eq. (4): 0 < q < 1
  EXPECT_EQ(b.task.apply_config(bad), CommandStatus::invalid);
  EXPECT_EQ(b.task.sliding_params(hal::Axis::x).gamma, base_config().axis[0].sliding.gamma) << "x not applied either";
  EXPECT_EQ(b.task.config().axis[0].sliding.gamma, base_config().axis[0].sliding.gamma);
}

TEST(TickTaskApplyConfig, WhileMovingOnlyTheLiveTunablePartIsAccepted) {
  Bench b;
  ASSERT_EQ(b.task.start_circle(CircleSpec{}), CommandStatus::ok);
  b.tick(5);
  ASSERT_TRUE(b.task.moving()) << "the dwell counts as moving";
  FirmwareConfig live = b.task.config();
  live.axis[0].sliding.gamma = 0.3;
  live.axis[1].pid.kp = 400.0;
  FirmwareConfig idle = live;
  idle.supervisor.axis[0].speed_max_mm_s = 100.0;
  EXPECT_EQ(b.task.apply_config(idle), CommandStatus::busy);
  EXPECT_EQ(b.task.sliding_params(hal::Axis::x).gamma, base_config().axis[0].sliding.gamma) << "nothing of a refused set";
  EXPECT_EQ(b.task.apply_config(live), CommandStatus::ok);
  EXPECT_EQ(b.task.sliding_params(hal::Axis::x).gamma, 0.3);
  EXPECT_EQ(b.task.pid_params(hal::Axis::y).kp, 400.0);
  EXPECT_EQ(b.task.config().supervisor.axis[0].speed_max_mm_s, base_config().supervisor.axis[0].speed_max_mm_s);
}

TEST(TickTaskApplyConfig, ANewEncoderCountIsRebasedSoThePositionDoesNotJump) {
  Bench b;
  b.board.counts = {2400, 0};
  b.tick();
  const double before_mm = b.task.last_record().axis[0].position_mm;
  FirmwareConfig c = b.task.config();
  c.axis[0].count_mm *= 2.0;
  ASSERT_EQ(b.task.apply_config(c), CommandStatus::ok);
  b.tick();
  EXPECT_NEAR(b.task.last_record().axis[0].position_mm, before_mm, 1e-12);
  b.board.counts = {2410, 0};
  b.tick();
  EXPECT_NEAR(b.task.last_record().axis[0].position_mm - before_mm, 10 * c.axis[0].count_mm, 1e-12) << "new scale";
}

TEST(TickTaskApplyConfig, AControllerChangeAtRestSelectsItAndHomeIsNotApplied) {
  Bench b;
  FirmwareConfig c = b.task.config();
  c.axis[1].controller = ControllerKind::pid;
  c.axis[0].home_position_mm = 99.0;
  ASSERT_EQ(b.task.apply_config(c), CommandStatus::ok);
  EXPECT_EQ(b.task.controller(hal::Axis::y), ControllerKind::pid);
  b.tick();
  EXPECT_NEAR(b.task.last_record().axis[0].position_mm, 6.0, 1e-12) << "zero() moves the frame, not apply_config()";
}

TEST(TickTaskStop, DwellHoldsAtOnceAndRestIsOk) {
  Bench b;
  EXPECT_EQ(b.task.stop(), CommandStatus::ok);
  EXPECT_EQ(b.task.state(), MotionState::disabled);
  ASSERT_EQ(b.task.start_circle(CircleSpec{}), CommandStatus::ok);
  b.tick();
  EXPECT_EQ(b.task.stop(), CommandStatus::ok);
  EXPECT_EQ(b.task.state(), MotionState::holding);
}

TEST(TickTaskZero, RefusedWhileMovingNonFiniteOrBeyondTheLimits) {
  Bench b;
  EXPECT_EQ(b.task.zero(hal::Axis::x, std::numeric_limits<double>::quiet_NaN()), CommandStatus::invalid);
  EXPECT_EQ(b.task.zero(hal::Axis::x, 1e4), CommandStatus::invalid);
  ASSERT_EQ(b.task.start_circle(CircleSpec{}), CommandStatus::ok);
  EXPECT_EQ(b.task.zero(hal::Axis::x, 0.0), CommandStatus::busy);
  b.task.disable();
  EXPECT_EQ(b.task.zero(hal::Axis::y, -3.0), CommandStatus::ok);
  b.tick();
  EXPECT_NEAR(b.task.last_record().axis[1].position_mm, -3.0, 1e-12);
}

TEST(TickTaskEstop, LatchesARemoteEstopThatClearsWithoutAnInputCause) {
  Bench b;
  ASSERT_EQ(b.task.hold_position(), CommandStatus::ok);
  EXPECT_EQ(b.task.estop(), CommandStatus::ok);
  b.tick();
  EXPECT_EQ(b.task.fault().reason, FaultReason::remote_estop);
  EXPECT_FALSE(b.board.written_enable[0]);
  EXPECT_EQ(b.board.written_code[0], 2048);
  EXPECT_EQ(b.task.clear_fault(), CommandStatus::ok);
  EXPECT_EQ(b.task.state(), MotionState::disabled);
}

TEST(StagedParams, HoldsOneEntryPerParameterOfTheTable) {
  EXPECT_GT(can::StagedParams::kCapacity, can::param_table().size());
  can::StagedParams s;
  for (const can::ParamDef& p : can::param_table()) ASSERT_TRUE(s.put(p.id, 1.0));
  ASSERT_TRUE(s.put(can::param_table()[0].id, 2.0));
  EXPECT_EQ(s.size(), can::param_table().size()) << "a second stage of an id overwrites";
  EXPECT_EQ(s.items()[0].value, 2.0);
}

}  // namespace
}  // namespace tnv::fw
