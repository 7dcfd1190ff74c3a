// A DAC whose output sticks at a code: the board's readback comparator
// latches it at the next tick, the firmware drops the enables (which the
// stuck DAC cannot override) in that same tick.
#include <gtest/gtest.h>

#include "tests/hil/fault_expect.hpp"

namespace tnv::hil {
namespace {

TEST(FaultDac, StuckXDacLatchesDacErrorAndTheEnableRemovesTheDrive) {
  const FaultCase c{.name = "dac_stuck",
                    .fault = {.kind = emu::FaultKind::dac_stuck,
                              .start_s = 3.0004,
                              .axis = hal::Axis::x,
                              .dac_code = test::kMidCode + 600}};  // about +49 mm/s
  const FaultObservation o = run_fault_case(test::fault_scenario(), c);
  test::expect_safe_at_latch(o, fw::FaultReason::dac_error, 0);
  test::expect_first_tick(o);
  EXPECT_EQ(o.after_latch.dac_output[0], test::kMidCode + 600) << "still stuck: only the enable makes it safe";
  // 0.6 ms at up to 49 mm/s before the tick that caught it.
  EXPECT_LT(o.deviation_um, 30.0) << "um from the reference";
}

}  // namespace
}  // namespace tnv::hil
