// The firmware's homing cycle on the emulated board: it homes both axes
// from seeded power-ups to within half a count of the index mark (motor
// side), the same frame within one count whatever the power-up position
// and encoder phase; motion is refused before homing when required; soft
// limits are relative to home; a missing switch or index ends in a
// homing_failed fault within the cycle's travel bounds, at rest.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>

#include "hal/axis.hpp"
#include "tests/hil/hil_rig.hpp"
#include "tools/hil/homing_run.hpp"

namespace tnv::hil {
namespace {

constexpr double kCountUm = 10.0 / 24000.0 * 1000.0;

TEST(HomingCycle, HomesWithinHalfACountAndRepeatsWithinOneOverSeeds) {
  const HomingSummary sum = run_homing(homing_scenario(), homing_firmware_config(), 12);
  ASSERT_EQ(sum.seeds.size(), 12u);
  for (const HomingSeedResult& r : sum.seeds) {
    ASSERT_TRUE(r.homed) << "seed " << r.seed << ": " << r.failure;
    for (const hal::Axis a : hal::kAxes) {
      const std::size_t i = hal::index(a);
      EXPECT_LE(std::fabs(r.home_error_um[i]), 0.5 * kCountUm + 1e-6) << "seed " << r.seed << ", " << hal::axis_label(a);
      EXPECT_LE(std::fabs(r.reading_error_um[i]), kCountUm + 1e-6)
          << "seed " << r.seed << ", " << hal::axis_label(a) << " reading at rest";
    }
    EXPECT_LE(r.time_s, 30.0) << "seed " << r.seed;
  }
  EXPECT_LE(sum.home_error_spread_um, kCountUm) << "repeatable within one count";
  EXPECT_LE(sum.home_error_um_max, 0.5) << "the issue's goal, um";
  // The seeds must really differ, or repeatability proves nothing.
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    EXPECT_NE(sum.seeds[0].offset_counts[i], sum.seeds[1].offset_counts[i]) << hal::kAxisNames[i];
    EXPECT_GT(std::fabs(sum.seeds[0].power_up_offset_mm[i] - sum.seeds[1].power_up_offset_mm[i]), 0.1)
        << hal::kAxisNames[i];
  }
}

TEST(HomingCycle, MotionRefusedBeforeHomingAndSoftLimitsAreRelativeToHome) {
  fw::FirmwareConfig config = homing_firmware_config();  // homing_required on
  config.supervisor.axis[0].position_min_mm = -30.0;
  config.supervisor.axis[0].position_max_mm = 40.0;
  test::HilRig rig(homing_scenario(), config);
  ASSERT_TRUE(rig.init_ok);
  for (int i = 0; i < 3; ++i) rig.tick();
  ASSERT_EQ(rig.task.hold_position(), fw::CommandStatus::ok);
  EXPECT_EQ(rig.task.start_move({hal::Axis::x, 1.0, 5.0, 0.02, 0.0}), fw::CommandStatus::not_homed);
  EXPECT_EQ(rig.task.start_circle(circle_spec_for(rig.scenario)), fw::CommandStatus::not_homed);
  ASSERT_EQ(rig.task.home(hal::axis_bit(hal::Axis::x)), fw::CommandStatus::ok);
  for (int k = 0; k < 30'000 && rig.task.homing(); ++k) rig.tick();
  ASSERT_TRUE(rig.task.homed(hal::Axis::x)) << fw::to_string(rig.task.homing_result(hal::Axis::x));
  const double x_mm = rig.task.standing_mm(hal::Axis::x);
  EXPECT_NEAR(x_mm, config.axis[0].homing.position_mm, 0.2) << "at rest just past the index, in the home frame";
  // position_max 40 mm is 60 mm above home (-20 mm): a move to 41 mm is refused, to 39 mm taken.
  EXPECT_EQ(rig.task.start_move({hal::Axis::x, 41.0 - x_mm, 20.0, 0.1, 0.0}), fw::CommandStatus::invalid);
  EXPECT_EQ(rig.task.start_move({hal::Axis::x, 39.0 - x_mm, 20.0, 0.1, 0.0}), fw::CommandStatus::ok);
  EXPECT_EQ(rig.task.start_move({hal::Axis::y, 1.0, 5.0, 0.02, 0.0}), fw::CommandStatus::busy);
}

struct Bounded {
  fw::FaultRecord fault;
  double travel_mm = 0.0;  // |table moved| from the command to the end
  double time_s = 0.0;
  bool at_rest = false;
};

Bounded home_until_fault(const emu::Scenario& s, const fw::FirmwareConfig& config) {
  test::HilRig rig(s, config);
  EXPECT_TRUE(rig.init_ok);
  for (int i = 0; i < 3; ++i) rig.tick();
  const double start_mm = rig.machine.truth(hal::Axis::x).position_mm;
  const double start_s = rig.machine.time_s();
  EXPECT_EQ(rig.task.home(hal::axis_bit(hal::Axis::x)), fw::CommandStatus::ok);
  for (int k = 0; k < 120'000 && rig.task.homing(); ++k) rig.tick();
  for (int k = 0; k < 100; ++k) rig.tick();
  return {rig.task.fault(), std::fabs(rig.machine.truth(hal::Axis::x).position_mm - start_mm),
          rig.machine.time_s() - start_s, std::fabs(rig.machine.truth(hal::Axis::x).speed_mm_s) < 1e-9};
}

TEST(HomingCycle, AMissingSwitchEndsInAFaultWithinTheSearchTravel) {
  emu::Scenario s = homing_scenario();
  s.board.axis[0].home_switch = false;  // no switch: the search runs its whole travel
  fw::FirmwareConfig config = homing_firmware_config();
  config.axis[0].homing.search_max_mm = 30.0;
  const Bounded b = home_until_fault(s, config);
  EXPECT_EQ(b.fault.reason, fw::FaultReason::homing_failed);
  EXPECT_EQ(b.fault.axis, 0);
  EXPECT_NEAR(b.fault.limit, 30.0, 1e-9);
  // Braking from 10 mm/s at the jog acceleration (1000 mm/s^2) adds 0.05 mm.
  EXPECT_GT(b.travel_mm, 29.9);
  EXPECT_LT(b.travel_mm, 30.2) << "the search must stop at its bound";
  EXPECT_LT(b.time_s, 30.0 / 10.0 + 0.5) << "bounded in time";
  EXPECT_TRUE(b.at_rest);
}

TEST(HomingCycle, AnIndexBeyondTheLatchTravelEndsInAFault) {
  fw::FirmwareConfig config = homing_firmware_config();
  config.axis[0].homing.latch_max_mm = 2.0;  // the x mark is 4.5 mm past the release
  const Bounded b = home_until_fault(homing_scenario(), config);
  EXPECT_EQ(b.fault.reason, fw::FaultReason::homing_failed);
  EXPECT_NEAR(b.fault.limit, 2.0, 1e-9);
  EXPECT_TRUE(b.at_rest);
}

}  // namespace
}  // namespace tnv::hil
