// Tick-timing faults: lost tick interrupts, a late tick, a stale snapshot.
#include <gtest/gtest.h>

#include "tests/hil/fault_expect.hpp"

namespace tnv::hil {
namespace {

using emu::FaultKind;

TEST(FaultTick, OneMissedTickIsToleratedAndCounted) {
  const FaultCase c{.name = "missed_tick_1",
                    .fault = {.kind = FaultKind::missed_tick, .start_s = 3.0004, .ticks = 1},
                    .give_up_s = 0.2};
  const FaultObservation o = run_fault_case(test::fault_scenario(), c);
  ASSERT_TRUE(o.error.empty()) << o.error;
  EXPECT_FALSE(o.detected) << "latched " << fw::to_string(o.fault.reason);
  EXPECT_EQ(o.counters.missed_ticks, 1u);
  EXPECT_TRUE(o.live_before_detection) << "the circle goes on";
}

TEST(FaultTick, ThreeMissedTicksTripTheWatchdogThenTheFirmwareLatchesMissedTicks) {
  const FaultCase c{.name = "missed_tick_3", .fault = {.kind = FaultKind::missed_tick, .start_s = 3.0004, .ticks = 3}};
  const FaultObservation o = run_fault_case(test::fault_scenario(), c);
  test::expect_safe_at_latch(o, fw::FaultReason::missed_ticks, -1);
  EXPECT_EQ(o.fault.value, 3.0) << "ticks lost";
  EXPECT_EQ(o.ticks_to_detect(), 1u) << "the first tick the firmware wakes for";
  // The last kick was at 3.000 s: the board's watchdog trips 30,100 clocks
  // later, before the firmware wakes at 3.004 s.
  EXPECT_TRUE(o.watchdog_tripped);
  ASSERT_TRUE(o.outputs_safe_s.has_value());
  EXPECT_NEAR(*o.outputs_safe_s, 3.00301, 1e-9) << "s";
}

TEST(FaultTick, TickLateByOneAndAHalfPeriodsLatchesLateTick) {
  // 25,000 clocks between kicks: below the watchdog's 30,000, so only the
  // supervisor's period check can see it, on the late tick itself.
  const FaultCase c{.name = "late_tick_1500us",
                    .fault = {.kind = FaultKind::late_tick, .start_s = 3.0004, .delay_us = 1500}};
  const FaultObservation o = run_fault_case(test::fault_scenario(), c);
  test::expect_safe_at_latch(o, fw::FaultReason::late_tick, -1);
  EXPECT_EQ(o.ticks_to_detect(), 1u) << "the late tick latches it";
  EXPECT_NEAR(o.detected_s, 3.0025, 1e-9) << "s: nominal 3.001 s, 1.5 ms late";
  EXPECT_TRUE(o.live_before_detection);
  EXPECT_FALSE(o.watchdog_tripped);
  EXPECT_EQ(o.fault.value, 25'000.0) << "measured period, clocks";
}

TEST(FaultTick, TickLateByOneAndAHalfPeriodsIsCountedToday) {
  // What the firmware does without the hook-up: counts it, keeps going.
  const FaultCase c{.name = "late_tick_1500us",
                    .fault = {.kind = FaultKind::late_tick, .start_s = 3.0004, .delay_us = 1500},
                    .give_up_s = 0.2};
  const FaultObservation o = run_fault_case(test::fault_scenario(), c);
  ASSERT_TRUE(o.error.empty()) << o.error;
  EXPECT_EQ(o.counters.late_ticks, 1u);
  EXPECT_FALSE(o.watchdog_tripped);
}

TEST(FaultTick, TickLateBeyondTheWatchdogTimeoutTripsTheBoardFirst) {
  const FaultCase c{.name = "late_tick_2500us",
                    .fault = {.kind = FaultKind::late_tick, .start_s = 3.0004, .delay_us = 2500}};
  const FaultObservation o = run_fault_case(test::fault_scenario(), c);
  // The board's watchdog names it today; once the supervisor sees the
  // period (tick_task hook-up) the root cause, late_tick, comes first.
  const fw::FaultReason named =
      o.fault.reason == fw::FaultReason::late_tick ? fw::FaultReason::late_tick : fw::FaultReason::watchdog_tripped;
  test::expect_safe_at_latch(o, named, -1);
  EXPECT_EQ(o.ticks_to_detect(), 1u);
  EXPECT_TRUE(o.watchdog_tripped);
  ASSERT_TRUE(o.outputs_safe_s.has_value());
  EXPECT_NEAR(*o.outputs_safe_s, 3.00301, 1e-9) << "s: 3.01 ms after the last kick at 3.000 s";
}

TEST(FaultTick, StaleSnapshotLatchesOnTheFirstRepeatedSequence) {
  const FaultCase c{.name = "stale_snapshot",
                    .fault = {.kind = FaultKind::stale_snapshot, .start_s = 3.0004, .duration_s = 0.005}};
  const FaultObservation o = run_fault_case(test::fault_scenario(), c);
  test::expect_safe_at_latch(o, fw::FaultReason::stale_snapshot, -1);
  test::expect_first_tick(o);
}

}  // namespace
}  // namespace tnv::hil
