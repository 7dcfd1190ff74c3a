// Z on the emulated machine, through the real driver and tick task: the
// head homes first and to its top, a Z move follows its command against the
// head's weight (reference plant "Z axis", d_g = -1 mm/s), and a head at
// rest, held or idle, does not sag.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include "hal/axis.hpp"
#include "tests/hil/hil_rig.hpp"
#include "tools/hil/homing_run.hpp"

namespace tnv::hil {
namespace {

constexpr hal::Axis kZ = hal::Axis::z;
constexpr std::size_t kZi = hal::index(kZ);
constexpr double kCountMm = 10.0 / 24000.0;

TEST(ZAxis, IsInTheListAndHomesFirst) {
  EXPECT_EQ(hal::axis_from_name("z"), kZ);
  EXPECT_EQ(hal::kHomingOrder[0], kZ);
  EXPECT_TRUE(fw::default_firmware_config().axis[kZi].homing.search_positive) << "Z's switch is at the top";
  for (const hal::Axis a : {hal::Axis::x, hal::Axis::y})
    EXPECT_FALSE(fw::default_firmware_config().axis[hal::index(a)].homing.search_positive);
}

TEST(ZAxis, HomesFirstUpToItsSwitchAtTheTopThenXAndY) {
  test::HilRig rig(homing_scenario(), homing_firmware_config());
  ASSERT_TRUE(rig.init_ok);
  for (int i = 0; i < 3; ++i) rig.tick();
  const double z_start_mm = rig.machine.truth(kZ).position_mm;
  ASSERT_LT(z_start_mm, -1.0) << "the head starts below its switch";
  ASSERT_EQ(rig.task.home(hal::kEveryAxis), fw::CommandStatus::ok);
  std::array<int, hal::kAxisCount> homed_at = hal::per_axis(-1);
  double z_highest_mm = z_start_mm;
  double xy_moved_while_z_homing_mm = 0.0;
  const double x0_mm = rig.machine.truth(hal::Axis::x).position_mm;
  const double y0_mm = rig.machine.truth(hal::Axis::y).position_mm;
  for (int k = 0; k < 60'000 && rig.task.homing(); ++k) {
    rig.tick();
    z_highest_mm = std::max(z_highest_mm, rig.machine.truth(kZ).position_mm);
    if (homed_at[kZi] < 0)
      xy_moved_while_z_homing_mm = std::max({xy_moved_while_z_homing_mm,
                                             std::fabs(rig.machine.truth(hal::Axis::x).position_mm - x0_mm),
                                             std::fabs(rig.machine.truth(hal::Axis::y).position_mm - y0_mm)});
    for (const hal::Axis a : hal::kAxes)
      if (homed_at[hal::index(a)] < 0 && rig.task.homed(a)) homed_at[hal::index(a)] = k;
  }
  ASSERT_FALSE(rig.task.fault().active()) << fw::to_string(rig.task.fault().reason);
  for (const hal::Axis a : hal::kAxes)
    ASSERT_TRUE(rig.task.homed(a)) << hal::axis_label(a) << ": " << fw::to_string(rig.task.homing_result(a));
  EXPECT_LT(homed_at[kZi], homed_at[hal::index(hal::Axis::x)]) << "Z homes before X";
  EXPECT_LT(homed_at[kZi], homed_at[hal::index(hal::Axis::y)]) << "Z homes before Y";
  EXPECT_EQ(xy_moved_while_z_homing_mm, 0.0) << "the table waits while the head homes";
  // Up to the switch at the top (0 mm), not into the hard stop 5 mm above it.
  EXPECT_GE(z_highest_mm, 0.0);
  EXPECT_LT(z_highest_mm, 2.0);
  // Home is the first mark below the switch's release (-5 mm): the head
  // rests there, in the home frame's -5 mm.
  for (int k = 0; k < 200; ++k) rig.tick();
  EXPECT_NEAR(rig.machine.truth(kZ).position_mm, -5.0, 0.05);
  EXPECT_NEAR(rig.task.last_record().axis[kZi].position_mm, -5.0, 0.05);
}

// A Z move from the power-up position: down 40 mm and back up 40 mm at
// 20 mm/s, against and with the head's weight.
TEST(ZAxis, AMoveFollowsItsCommandUnderTheHeadsWeightAndHoldsAtRest) {
  const emu::Scenario s;  // the reference plant: d_g = -1 mm/s
  test::HilRig rig(s);
  ASSERT_TRUE(rig.init_ok);
  for (int i = 0; i < 3; ++i) rig.tick();
  ASSERT_EQ(rig.task.hold_position(), fw::CommandStatus::ok);
  for (int i = 0; i < 100; ++i) rig.tick();
  const double start_mm = rig.machine.truth(kZ).position_mm;
  EXPECT_NEAR(start_mm, s.z_axis.start_mm, 1e-9) << "held at power-up: no sag";
  for (const double distance_mm : {-40.0, 40.0}) {
    const double from_mm = rig.machine.truth(kZ).position_mm;
    ASSERT_EQ(rig.task.start_move({kZ, distance_mm, 20.0, 0.1, 0.0}), fw::CommandStatus::ok);
    double max_following_mm = 0.0;
    for (int k = 0; k < 10'000 && rig.task.moving(); ++k) {
      rig.tick();
      const fw::AxisTickRecord& r = rig.task.last_record().axis[kZi];
      max_following_mm = std::max(max_following_mm, std::fabs(r.reference_mm - r.position_mm));
    }
    ASSERT_FALSE(rig.task.moving());
    ASSERT_FALSE(rig.task.fault().active()) << fw::to_string(rig.task.fault().reason) << " axis "
                                             << static_cast<int>(rig.task.fault().axis) << " after "
                                             << max_following_mm << " mm following";
    // Settle, then hold for 1 s: the error at rest must stay within a few
    // counts with d_g pulling the head down all the time.
    for (int k = 0; k < 300; ++k) rig.tick();
    double max_rest_error_mm = 0.0;
    for (int k = 0; k < 1000; ++k) {
      rig.tick();
      max_rest_error_mm =
          std::max(max_rest_error_mm, std::fabs(rig.machine.truth(kZ).position_mm - (from_mm + distance_mm)));
    }
    const std::string leg = distance_mm < 0.0 ? "down" : "up";
    RecordProperty("max_following_um_" + leg, std::to_string(max_following_mm * 1000.0));
    RecordProperty("max_rest_error_um_" + leg, std::to_string(max_rest_error_mm * 1000.0));
    RecordProperty("rest_command_mm_s_" + leg, std::to_string(rig.task.last_record().axis[kZi].command_mm_s));
    EXPECT_LT(max_following_mm, 0.05) << "moving " << distance_mm << " mm";
    EXPECT_LT(max_rest_error_mm, 3.0 * kCountMm) << "held after " << distance_mm << " mm";
    // The controller holds the weight: its command at rest is d_g's +1 mm/s
    // within the stiction band (|u + d_g| <= f_s keeps the head stuck).
    EXPECT_LE(std::fabs(rig.task.last_record().axis[kZi].command_mm_s + s.z_axis.gravity_mm_s),
              s.plant[kZi].stiction_mm_s);
  }
  // The table's axes stayed where they were.
  for (const hal::Axis a : {hal::Axis::x, hal::Axis::y})
    EXPECT_NEAR(rig.machine.truth(a).position_mm, emu::power_up_position_mm(s, a), kCountMm) << hal::axis_label(a);
}

TEST(ZAxis, AnIdleHeadDoesNotSag) {
  const emu::Scenario s;
  test::HilRig rig(s);
  ASSERT_TRUE(rig.init_ok);
  const double start_mm = rig.machine.truth(kZ).position_mm;
  for (int k = 0; k < 2000; ++k) rig.tick();  // servo off, 2 s
  EXPECT_FALSE(rig.machine.board_outputs().enabled[kZi]);
  EXPECT_EQ(rig.machine.truth(kZ).position_mm, start_mm) << "|d_g| = 1 <= f_s = 4: the head stays stuck";
  EXPECT_TRUE(rig.machine.truth(kZ).stuck);
}

}  // namespace
}  // namespace tnv::hil
