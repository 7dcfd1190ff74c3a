// Fault reaction over a board transport ([io] latencies, bench-no-cut): the
// same tick detects the fault, and the safe outputs land the transport's
// latency later, which the fault harness waits for instead of missing.
#include <gtest/gtest.h>

#include "emulator/scenario_file.hpp"
#include "tools/hil/fault_run.hpp"

namespace tnv::hil {
namespace {

TEST(FaultTransport, AnEstopIsDetectedInTheSameTickAndTheOutputsLandSafeOneTransportLater) {
  const FaultCase c{.name = "estop",
                    .fault = {.kind = emu::FaultKind::estop, .start_s = 3.0004},
                    .expected = fw::FaultReason::estop};
  emu::Scenario ideal = *emu::builtin_scenario("no-cut");
  emu::Scenario transport = ideal;
  transport.io.read_latency_us = 100.0;
  transport.io.write_latency_us = 50.0;  // no jitter: the landing time is exact
  const FaultObservation a = run_fault_case(ideal, c);
  const FaultObservation b = run_fault_case(transport, c);
  ASSERT_TRUE(a.detected && b.detected) << a.error << b.error;
  EXPECT_EQ(a.fault.reason, fw::FaultReason::estop);
  EXPECT_EQ(b.fault.reason, fw::FaultReason::estop);
  EXPECT_EQ(a.ticks_to_detect(), b.ticks_to_detect());
  ASSERT_TRUE(a.time_to_safe_s() && b.time_to_safe_s()) << "the harness saw the safe outputs";
  const double later_us = (*b.time_to_safe_s() - *a.time_to_safe_s()) * 1e6;
  // Read + write latency (150 us) plus the tick's own work, on the 10 us grid.
  EXPECT_GE(later_us, 150.0 - 1e-6);
  EXPECT_LE(later_us, 200.0);
  EXPECT_TRUE(b.after_latch.safe(2048));
}

}  // namespace
}  // namespace tnv::hil
