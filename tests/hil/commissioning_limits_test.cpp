// What the tightened ranges of the safety parameters buy: a runaway axis
// (drive gain sign flipped mid-circle) with the widest following-error
// and speed limits the parameter table allows, against the values
// (floor 100 mm, lag 10 s; speed limit 10,000 mm/s, the old range's top),
// which the table now refuses. docs/safety.md "Commissioning".
#include <gtest/gtest.h>

#include "firmware/can/param_table.hpp"
#include "tests/hil/fault_expect.hpp"

namespace tnv::hil {
namespace {

FaultObservation runaway_with_limits(double floor_mm, double lag_s, double speed_max_mm_s, double give_up_s) {
  fw::FirmwareConfig config = fw::default_firmware_config();
  for (fw::AxisLimits& a : config.supervisor.axis) {
    a.following.floor_mm = floor_mm;
    a.following.lag_s = lag_s;
    a.speed_max_mm_s = speed_max_mm_s;
  }
  const FaultCase c{.name = "runaway",
                    .fault = {.kind = emu::FaultKind::runaway, .start_s = 3.0004, .axis = hal::Axis::x},
                    .give_up_s = give_up_s};
  return run_fault_case(test::fault_scenario(), c, fw::ControllerKind::rdvsc, nullptr, &config);
}

TEST(CommissioningLimits, TheWidestAllowedFollowingLimitsStillStopARunawayWithinMillimetres) {
  const double floor_max_mm = fw::can::find_param("x.limits.following_floor_mm")->max;
  const double lag_max_s = fw::can::find_param("x.limits.following_lag_s")->max;
  const double speed_max_mm_s = fw::can::find_param("x.limits.speed_max_mm_s")->max;
  const FaultObservation widest = runaway_with_limits(floor_max_mm, lag_max_s, speed_max_mm_s, 2.0);
  ASSERT_TRUE(widest.error.empty()) << widest.error;
  ASSERT_TRUE(widest.detected);
  // The motion-plausibility check (runaway, 3 ticks) now usually wins over
  // the following-error limit; either way the widest limits bound the run.
  EXPECT_TRUE(widest.fault.reason == fw::FaultReason::following_error ||
              widest.fault.reason == fw::FaultReason::speed_limit || widest.fault.reason == fw::FaultReason::runaway)
      << fw::to_string(widest.fault.reason);
  RecordProperty("widest_reason", fw::to_string(widest.fault.reason));
  RecordProperty("widest_deviation_um", std::to_string(widest.deviation_um));
  RecordProperty("widest_ticks", std::to_string(widest.ticks_to_detect()));
  // The limit at the circle's 2 mm/s is floor + lag * 2 mm/s; the table
  // overshoots it by at most a tick of a runaway's speed.
  EXPECT_LT(widest.deviation_um, (floor_max_mm + lag_max_s * 2.0) * 1e3 * 1.5);

  // The values: refused by the table, and they would let the same runaway run far further.
  EXPECT_EQ(fw::can::check_value(*fw::can::find_param("x.limits.following_floor_mm"), 100.0),
            fw::can::ErrorCode::out_of_range);
  const FaultObservation abused = runaway_with_limits(100.0, 10.0, 1e4, 2.0);
  ASSERT_TRUE(abused.error.empty()) << abused.error;
  RecordProperty("abused_reason", abused.detected ? fw::to_string(abused.fault.reason) : "none");
  RecordProperty("abused_ticks", std::to_string(abused.ticks_to_detect()));
  RecordProperty("abused_deviation_um", std::to_string(abused.deviation_um));
  // The runaway check does not depend on these limits: it still stops the
  // table within 3 ticks and 20 µm (docs/safety.md "Motion plausibility").
  ASSERT_TRUE(abused.detected) << "the abused limits let the runaway run";
  EXPECT_EQ(abused.fault.reason, fw::FaultReason::runaway) << fw::to_string(abused.fault.reason);
  EXPECT_LE(abused.ticks_to_detect(), 3);
  EXPECT_LT(abused.deviation_um, 20.0);
}

}  // namespace
}  // namespace tnv::hil
