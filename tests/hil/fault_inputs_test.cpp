// Wired inputs: e-stop, servopack alarm, limit switch. Each latches on the
// first tick that sees it, makes that tick's outputs safe at the board, and
// cannot be cleared while the input is still asserted.
#include <gtest/gtest.h>

#include "tests/hil/fault_expect.hpp"

namespace tnv::hil {
namespace {

using emu::FaultKind;
using test::expect_first_tick;
using test::expect_safe_at_latch;

// Clearing: refused while the input is asserted, accepted once it is gone
// (the scheduled window ends at release_s), and the axis stays off.
void expect_clear_only_after_release(HilRig& rig, double release_s) {
  EXPECT_EQ(rig.task.clear_fault(), fw::CommandStatus::cause_present);
  while (rig.machine.time_s() < release_s - 1e-3) rig.tick();  // the last tick before the release
  EXPECT_EQ(rig.task.clear_fault(), fw::CommandStatus::cause_present) << "the last snapshot still shows the input";
  rig.tick();
  EXPECT_EQ(rig.task.clear_fault(), fw::CommandStatus::ok);
  rig.tick();
  EXPECT_EQ(rig.task.state(), fw::MotionState::disabled) << "cleared to disabled, never back into motion";
  EXPECT_FALSE(rig.machine.board_outputs().enabled[0]);
}

TEST(FaultInputs, EstopMidCircle) {
  const FaultCase c{.name = "estop", .fault = {.kind = FaultKind::estop, .start_s = 3.0004, .duration_s = 0.05}};
  std::unique_ptr<HilRig> rig;
  const FaultObservation o = run_fault_case(test::fault_scenario(), c, fw::ControllerKind::rdvsc, &rig);
  expect_safe_at_latch(o, fw::FaultReason::estop, -1);
  expect_first_tick(o);
  ASSERT_TRUE(rig);
  expect_clear_only_after_release(*rig, 3.0504);
}

TEST(FaultInputs, ServoAlarmOnYMidCircle) {
  const FaultCase c{
      .name = "servo_alarm",
      .fault = {.kind = FaultKind::servo_alarm, .start_s = 3.0004, .duration_s = 0.05, .axis = hal::Axis::y}};
  std::unique_ptr<HilRig> rig;
  const FaultObservation o = run_fault_case(test::fault_scenario(), c, fw::ControllerKind::rdvsc, &rig);
  expect_safe_at_latch(o, fw::FaultReason::servo_alarm, 1);
  expect_first_tick(o);
  ASSERT_TRUE(rig);
  expect_clear_only_after_release(*rig, 3.0504);
}

TEST(FaultInputs, LimitSwitchWhileJoggingIntoIt) {
  const FaultCase c{.name = "limit_switch",
                    .fault = {.kind = FaultKind::limit_switch,
                              .start_s = 1.0004,
                              .duration_s = 0.05,
                              .axis = hal::Axis::x,
                              .positive_side = true},
                    .motion = FaultMotion::jog_x};
  std::unique_ptr<HilRig> rig;
  const FaultObservation o = run_fault_case(test::fault_scenario(), c, fw::ControllerKind::rdvsc, &rig);
  expect_safe_at_latch(o, fw::FaultReason::limit_switch, 0);
  expect_first_tick(o);
  ASSERT_TRUE(rig);
  EXPECT_EQ(rig->task.jog(hal::Axis::x, 20.0), fw::CommandStatus::faulted) << "the jog key does nothing now";
  expect_clear_only_after_release(*rig, 1.0504);
}

}  // namespace
}  // namespace tnv::hil
