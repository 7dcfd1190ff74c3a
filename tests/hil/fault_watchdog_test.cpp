// The board's hardware watchdog catches a firmware that stops ticking: the
// outputs go safe at the board with no help from the firmware.
#include <gtest/gtest.h>

#include "tests/hil/fault_expect.hpp"

namespace tnv::hil {
namespace {

TEST(FaultWatchdog, AHungFirmwareLosesItsOutputs3msAfterItsLastKick) {
  const WatchdogObservation o = run_watchdog_case(test::fault_scenario(), 3.0, 10.0);
  ASSERT_TRUE(o.error.empty()) << o.error;
  ASSERT_TRUE(o.trip_s.has_value()) << "the watchdog never tripped";
  // WATCHDOG_TIMEOUT 30,000 clocks: trips at the first 10 us boundary beyond it.
  EXPECT_NEAR(*o.trip_s - o.last_kick_s, 3.01e-3, 1e-9) << "s from the last kick to the trip";
  EXPECT_TRUE(o.at_trip.safe(test::kMidCode)) << "DAC registers mid-scale, enables off, by the board alone";
  EXPECT_EQ(o.command_at_trip_mm_s[0], 0.0) << "mm/s reaching the X servopack";
  EXPECT_EQ(o.command_at_trip_mm_s[1], 0.0) << "mm/s reaching the Y servopack";
  // Back after 10 ms: the firmware latches the lost ticks, and cannot clear
  // while the board still reports the trip; the operator's board reset can.
  EXPECT_EQ(o.fault_on_return.reason, fw::FaultReason::missed_ticks);
  EXPECT_EQ(o.clear_while_tripped, fw::CommandStatus::cause_present);
  EXPECT_EQ(o.clear_after_reset, fw::CommandStatus::ok);
}

TEST(FaultWatchdog, TwoLostTicksAreWithinTheTimeout) {
  const WatchdogObservation o = run_watchdog_case(test::fault_scenario(), 3.0, 2.0);
  ASSERT_TRUE(o.error.empty()) << o.error;
  EXPECT_FALSE(o.trip_s.has_value()) << "3 ms between kicks is exactly the timeout, not beyond it";
  EXPECT_FALSE(o.fault_on_return.active()) << fw::to_string(o.fault_on_return.reason);
}

}  // namespace
}  // namespace tnv::hil
