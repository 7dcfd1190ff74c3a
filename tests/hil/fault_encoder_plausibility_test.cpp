// Counts the table cannot have made (encoder_jump) and a snapshot that
// goes backwards (snapshot_replayed): both caught on the first tick that
// reads them, before anything is computed from the bad data.
#include <gtest/gtest.h>

#include "tests/hil/fault_expect.hpp"

namespace tnv::hil {
namespace {

FaultObservation jump_on(hal::Axis axis, std::int32_t counts, fw::ControllerKind controller) {
  const FaultCase c{.name = "encoder_jump",
                    .fault = {.kind = emu::FaultKind::encoder_jump, .start_s = 3.0004, .axis = axis, .counts = counts}};
  return run_fault_case(test::fault_scenario(), c, controller);
}

TEST(FaultEncoderPlausibility, AJumpOf100CountsIsCaughtOnTheFirstTick) {
  for (const fw::ControllerKind controller : {fw::ControllerKind::rdvsc, fw::ControllerKind::dvsc, fw::ControllerKind::pid}) {
    SCOPED_TRACE(fw::to_string(controller));
    const FaultObservation o = jump_on(hal::Axis::x, 100, controller);
    test::expect_safe_at_latch(o, fw::FaultReason::encoder_implausible, 0);
    test::expect_first_tick(o);
    EXPECT_GT(std::fabs(o.fault.value), o.fault.limit) << "mm off the prediction vs the reachable spread";
    EXPECT_LT(o.deviation_um, 5.0) << "the table itself never moved off";
  }
}

TEST(FaultEncoderPlausibility, APermanentNegativeOffsetOnYIsCaught) {
  const FaultObservation o = jump_on(hal::Axis::y, -120, fw::ControllerKind::rdvsc);
  test::expect_safe_at_latch(o, fw::FaultReason::encoder_implausible, 1);
  test::expect_first_tick(o);
}

TEST(FaultEncoderPlausibility, AJumpWithinTheReachableSpreadIsNotAFault) {
  // 10 counts (4.2 um) is a step the table can make in a tick: the check
  // must not call it implausible (the following error still watches it).
  const FaultObservation o = jump_on(hal::Axis::x, 10, fw::ControllerKind::rdvsc);
  ASSERT_TRUE(o.error.empty()) << o.error;
  EXPECT_FALSE(o.detected) << "latched " << fw::to_string(o.fault.reason);
}

TEST(FaultEncoderPlausibility, AReplayedSnapshotIsStaleAndCorruptsNoCounter) {
  const FaultCase c{.name = "snapshot_replayed", .fault = {.kind = emu::FaultKind::snapshot_replayed, .start_s = 3.0004}};
  const FaultObservation o = run_fault_case(test::fault_scenario(), c);
  test::expect_safe_at_latch(o, fw::FaultReason::stale_snapshot, -1);
  test::expect_first_tick(o);
  EXPECT_EQ(o.counters.missed_ticks, 0u) << "a backwards sequence is not 4 billion lost ticks";
  EXPECT_EQ(o.counters.late_ticks, 0u);
}

}  // namespace
}  // namespace tnv::hil
