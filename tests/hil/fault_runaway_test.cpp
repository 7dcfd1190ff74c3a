// A runaway axis: the drive's gain sign flips (positive feedback). Nothing
// on the board knows; the motion plausibility check sees the table speed up
// against its command, or at speed pushed against it (motion_plausibility.hpp),
// long before the following error would (9 ticks, 110 um on the S1 circle
// with the following error alone).
#include <gtest/gtest.h>

#include "tests/hil/fault_expect.hpp"

namespace tnv::hil {
namespace {

FaultObservation runaway_on(FaultMotion motion, double start_s, fw::ControllerKind controller) {
  const FaultCase c{.name = "runaway",
                    .fault = {.kind = emu::FaultKind::runaway, .start_s = start_s, .axis = hal::Axis::x},
                    .motion = motion};
  return run_fault_case(test::fault_scenario(), c, controller);
}

TEST(FaultRunaway, FlippedGainOnTheCircleIsCaughtWithin3TicksAnd20Um) {
  for (const fw::ControllerKind controller : {fw::ControllerKind::rdvsc, fw::ControllerKind::dvsc, fw::ControllerKind::pid}) {
    SCOPED_TRACE(fw::to_string(controller));
    const FaultObservation o = runaway_on(FaultMotion::circle, 3.0004, controller);
    test::expect_safe_at_latch(o, fw::FaultReason::runaway, 0);
    EXPECT_TRUE(o.live_before_detection);
    EXPECT_GT(o.fault.value, o.fault.limit) << "mm gained against the command vs the limit";
    EXPECT_LE(o.ticks_to_detect(), 3u);
    EXPECT_LT(o.deviation_um, 20.0) << "um from the reference before the trip";
  }
}

TEST(FaultRunaway, FlippedGainWhileJoggingIsCaughtBeforeTheTableTurns) {
  // At 20 mm/s the table has to brake before it can run the wrong way; the
  // push check sees the brake (4 ticks and 51..64 um with the step check alone).
  for (const fw::ControllerKind controller : {fw::ControllerKind::rdvsc, fw::ControllerKind::dvsc, fw::ControllerKind::pid}) {
    SCOPED_TRACE(fw::to_string(controller));
    const FaultObservation o = runaway_on(FaultMotion::jog_x, 1.0004, controller);
    test::expect_safe_at_latch(o, fw::FaultReason::runaway, 0);
    EXPECT_GT(o.fault.value, o.fault.limit) << "mm/s of input against the command vs the limit";
    EXPECT_LE(o.ticks_to_detect(), 3u);
    EXPECT_LT(o.deviation_um, 20.0) << "um from the reference before the trip";
  }
}

}  // namespace
}  // namespace tnv::hil
