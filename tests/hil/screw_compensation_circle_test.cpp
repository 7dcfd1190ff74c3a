// The goal for backlash compensation: on the S1 circle with 10 um
// of backlash on both screws, the compensated axis' true contour error (the
// table, which the motor-side encoder does not see) is at most half the
// uncompensated one.
#include <gtest/gtest.h>

#include "emulator/scenario_file.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tools/hil/circle_run.hpp"

namespace tnv::hil {
namespace {

TEST(ScrewCompensationCircle, TenMicrometresOfBacklashCompensatedHalveTheTrueContourErrorAtLeast) {
  emu::Scenario s = *emu::builtin_scenario("no-cut");
  s.plant[0].backlash_um = s.plant[1].backlash_um = 10.0;
  const fw::FirmwareConfig plain = fw::default_firmware_config();
  fw::FirmwareConfig compensated = plain;
  for (fw::AxisConfig& a : compensated.axis) a.screw.backlash_mm = 0.010;
  ASSERT_TRUE(fw::validate(compensated).ok());

  const CircleRunResult off = run_circle(s, plain, fw::ControllerKind::rdvsc);
  const CircleRunResult on = run_circle(s, compensated, fw::ControllerKind::rdvsc);
  ASSERT_TRUE(off.completed) << off.error;
  ASSERT_TRUE(on.completed) << on.error;
  EXPECT_LE(on.true_table_stats.max_um, 0.5 * off.true_table_stats.max_um)
      << "compensated " << on.true_table_stats.max_um << " um, uncompensated " << off.true_table_stats.max_um;
  EXPECT_LE(on.true_table_stats.mean_um, 0.5 * off.true_table_stats.mean_um);
  // Uncompensated, the lash shows in the truth (the run is a real test of it).
  EXPECT_GT(off.true_table_stats.max_um, 4.0);
}

}  // namespace
}  // namespace tnv::hil
