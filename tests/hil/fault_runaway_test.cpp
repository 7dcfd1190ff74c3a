// A runaway axis: the drive's gain sign flips mid-circle (positive
// feedback). Nothing on the board knows; the following error finds it.
#include <gtest/gtest.h>

#include "tests/hil/fault_expect.hpp"

namespace tnv::hil {
namespace {

TEST(FaultRunaway, FlippedGainOnXIsCaughtByTheFollowingError) {
  const FaultCase c{.name = "runaway",
                    .fault = {.kind = emu::FaultKind::runaway, .start_s = 3.0004, .axis = hal::Axis::x}};
  const FaultObservation o = run_fault_case(test::fault_scenario(), c);
  test::expect_safe_at_latch(o, fw::FaultReason::following_error, 0);
  EXPECT_TRUE(o.live_before_detection);
  EXPECT_GT(std::fabs(o.fault.value), o.fault.limit) << "mm";
  // Measured figures (docs/safety.md), bounded so a regression shows.
  EXPECT_LE(o.ticks_to_detect(), 20u);
  EXPECT_LT(o.deviation_um, 300.0) << "um from the reference before the trip";
}

}  // namespace
}  // namespace tnv::hil
