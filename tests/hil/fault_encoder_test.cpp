// Encoder faults: an illegal A/B transition (the board's decoder latches it)
// and a dead encoder (nothing latches: the following error finds it).
#include <gtest/gtest.h>

#include "tests/hil/fault_expect.hpp"

namespace tnv::hil {
namespace {

using emu::FaultKind;

TEST(FaultEncoder, IllegalTransitionOnXLatchesEncoderError) {
  const FaultCase c{.name = "encoder_illegal",
                    .fault = {.kind = FaultKind::encoder_illegal, .start_s = 3.0004, .axis = hal::Axis::x}};
  std::unique_ptr<HilRig> rig;
  const FaultObservation o = run_fault_case(test::fault_scenario(), c, fw::ControllerKind::rdvsc, &rig);
  test::expect_safe_at_latch(o, fw::FaultReason::encoder_error, 0);
  test::expect_first_tick(o);
  ASSERT_TRUE(rig);
  // The board's latch is sticky: the first clear (the CAN clear_faults
  // command) resets it but answers cause_present, and the outputs stay safe...
  EXPECT_EQ(rig->task.clear_fault(), fw::CommandStatus::cause_present);
  rig->tick();
  EXPECT_EQ(rig->task.state(), fw::MotionState::faulted);
  EXPECT_EQ(rig->task.fault().reason, fw::FaultReason::encoder_error);
  EXPECT_FALSE(rig->machine.board_outputs().enabled[0]);
  // ...the next snapshot shows the latch gone, so the second clear holds.
  EXPECT_EQ(rig->task.clear_fault(), fw::CommandStatus::ok);
  rig->tick();
  EXPECT_EQ(rig->task.state(), fw::MotionState::disabled);
}

TEST(FaultEncoder, DeadEncoderOnYIsCaughtByTheFollowingError) {
  // Y moves at about 1.35 mm/s 2.5 s into the circle; its count freezes.
  const FaultCase c{.name = "encoder_dead",
                    .fault = {.kind = FaultKind::encoder_dead, .start_s = 3.0004, .axis = hal::Axis::y}};
  const FaultObservation o = run_fault_case(test::fault_scenario(), c);
  test::expect_safe_at_latch(o, fw::FaultReason::following_error, 1);
  EXPECT_TRUE(o.live_before_detection);
  // The frozen reading falls behind the reference at the reference speed:
  // the trip comes when that reaches floor + lag x speed (about 0.077 mm).
  EXPECT_GE(o.ticks_to_detect(), 40u);
  EXPECT_LE(o.ticks_to_detect(), 80u);
  EXPECT_GT(std::fabs(o.fault.value), o.fault.limit) << "mm";
  EXPECT_LT(std::fabs(o.fault.value), o.fault.limit + 0.01) << "mm: tripped as soon as it crossed";
  // Meanwhile the loop, blind, drives the real table away: how far is a
  // measured figure (docs/safety.md), bounded here so a regression shows.
  EXPECT_LT(o.deviation_um, 5000.0) << "um from the reference before the trip";
}

}  // namespace
}  // namespace tnv::hil
