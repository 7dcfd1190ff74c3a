// On any fault the outputs are safe within one tick, seen at the register
// level of the emulated board and in the table physics.
#include <gtest/gtest.h>

#include "emulator/scenario_file.hpp"
#include "tests/hil/hil_rig.hpp"

namespace tnv::hil {
namespace {

namespace regs = hal::regs;

void expect_outputs_safe(test::HilRig& rig, const char* what) {
  EXPECT_EQ(rig.reg(regs::kDacX), 2048u) << what << ": X DAC not at 0 V";
  EXPECT_EQ(rig.reg(regs::kDacY), 2048u) << what << ": Y DAC not at 0 V";
  EXPECT_EQ(rig.reg(regs::kOutputs) & (regs::kOutputEnableX | regs::kOutputEnableY), 0u) << what << ": enables on";
  rig.machine.advance_clocks(100);  // one sub-step later the servopacks see no command
  EXPECT_EQ(rig.machine.truth(hal::Axis::x).command_mm_s, 0.0) << what;
  EXPECT_EQ(rig.machine.truth(hal::Axis::y).command_mm_s, 0.0) << what;
}

void start_and_run(test::HilRig& rig, int ticks) {
  for (int i = 0; i < 3; ++i) rig.tick();
  ASSERT_EQ(rig.task.start_circle(circle_spec_for(rig.scenario)), fw::CommandStatus::ok);
  for (int i = 0; i < ticks; ++i) rig.tick();
}

TEST(SafeStop, AJammedAxisTripZeroesTheDacsAndDropsEnablesInTheSameTick) {
  // A jammed X axis (stiction above the DAC's full-scale command) cannot
  // follow the circle: the loop drives harder and harder without a count
  // until the stall monitor trips (before the following error would).
  emu::Scenario jammed = *emu::builtin_scenario("no-cut");
  jammed.plant[0].coulomb_mm_s = 200.0;
  jammed.plant[0].stiction_mm_s = 200.0;
  test::HilRig rig(jammed);
  ASSERT_TRUE(rig.init_ok);
  start_and_run(rig, 500);  // end of dwell: motion starts
  int ticks = 0;
  while (rig.task.state() != fw::MotionState::faulted && ticks < 20'000) {
    rig.tick();
    ++ticks;
    if (rig.task.state() != fw::MotionState::faulted) {
      ASSERT_NE(rig.reg(regs::kOutputs) & regs::kOutputEnableX, 0u) << "enable dropped before the fault";
    }
  }
  ASSERT_EQ(rig.task.state(), fw::MotionState::faulted) << "the jammed axis never tripped";
  EXPECT_EQ(rig.task.fault().reason, fw::FaultReason::encoder_stall);
  EXPECT_EQ(rig.task.fault().axis, 0);
  EXPECT_EQ(rig.task.fault().tick, rig.task.counters().ticks);
  expect_outputs_safe(rig, "stall trip");
}

TEST(SafeStop, EstopMidCircleMakesOutputsSafeAtTheNextTick) {
  test::HilRig rig(*emu::builtin_scenario("cut-900"));
  ASSERT_TRUE(rig.init_ok);
  start_and_run(rig, 3000);
  ASSERT_EQ(rig.task.state(), fw::MotionState::moving);
  rig.machine.set_estop(true);
  rig.tick();
  EXPECT_EQ(rig.task.fault().reason, fw::FaultReason::estop);
  expect_outputs_safe(rig, "e-stop");
  EXPECT_EQ(rig.task.clear_fault(), fw::CommandStatus::cause_present);
  rig.machine.set_estop(false);
  rig.tick();
  EXPECT_EQ(rig.task.clear_fault(), fw::CommandStatus::ok);
}

TEST(SafeStop, BoardWatchdogZeroesOutputsWhenTheFirmwareStopsTicking) {
  test::HilRig rig(*emu::builtin_scenario("no-cut"));
  ASSERT_TRUE(rig.init_ok);
  start_and_run(rig, 1000);
  ASSERT_NE(rig.reg(regs::kOutputs) & regs::kOutputEnableX, 0u);
  // The firmware hangs: the board keeps ticking, nobody kicks the watchdog.
  for (int i = 0; i < 4; ++i) rig.machine.advance_to_next_tick();
  EXPECT_NE(rig.reg(regs::kInputs) & regs::kInputWatchdogTripped, 0u);
  EXPECT_EQ(rig.machine.truth(hal::Axis::x).command_mm_s, 0.0);
  EXPECT_EQ(rig.machine.truth(hal::Axis::y).command_mm_s, 0.0);
  // When the firmware comes back it faults (4 lost ticks is beyond the
  // tolerated 2) and cannot clear while the board reports the trip.
  rig.tick();
  EXPECT_EQ(rig.task.state(), fw::MotionState::faulted);
  EXPECT_EQ(rig.task.fault().reason, fw::FaultReason::missed_ticks);
  EXPECT_EQ(rig.task.clear_fault(), fw::CommandStatus::cause_present);
}

}  // namespace
}  // namespace tnv::hil
