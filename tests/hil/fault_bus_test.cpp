// Register-bus read errors: the batched snapshot read fails; the tick uses
// nothing from it, latches bus_error and still writes safe outputs.
#include <gtest/gtest.h>

#include "tests/hil/fault_expect.hpp"

namespace tnv::hil {
namespace {

TEST(FaultBus, ReadErrorLatchesBusErrorAndTheWriteStillMakesOutputsSafe) {
  const FaultCase c{.name = "bus_read_error",
                    .fault = {.kind = emu::FaultKind::bus_read_error, .start_s = 3.0004, .duration_s = 0.001}};
  std::unique_ptr<HilRig> rig;
  const FaultObservation o = run_fault_case(test::fault_scenario(), c, fw::ControllerKind::rdvsc, &rig);
  test::expect_safe_at_latch(o, fw::FaultReason::bus_error, -1);
  test::expect_first_tick(o);
  EXPECT_EQ(o.counters.bus_errors, 1u);
  ASSERT_TRUE(rig);
  rig->tick();  // the window is over: reads work again
  EXPECT_EQ(rig->task.counters().bus_errors, 1u);
  EXPECT_EQ(rig->task.clear_fault(), fw::CommandStatus::ok) << "a transient bus error clears once it is gone";
}

TEST(FaultBus, ClearFaultIsRefusedWhileTheBoardDoesNotAnswer) {
  const FaultCase c{.name = "bus_read_error", .fault = {.kind = emu::FaultKind::bus_read_error, .start_s = 3.0004}};
  std::unique_ptr<HilRig> rig;
  const FaultObservation o = run_fault_case(test::fault_scenario(), c, fw::ControllerKind::rdvsc, &rig);
  test::expect_safe_at_latch(o, fw::FaultReason::bus_error, -1);
  ASSERT_TRUE(rig);
  for (int i = 0; i < 3; ++i) {
    rig->tick();  // reads keep failing
    EXPECT_EQ(rig->task.clear_fault(), fw::CommandStatus::cause_present) << "tick " << i;
    EXPECT_EQ(rig->task.state(), fw::MotionState::faulted);
  }
}

}  // namespace
}  // namespace tnv::hil
