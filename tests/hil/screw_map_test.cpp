// Lead-error measurement: the file read strictly and, on the bench table,
// the measured table taking the true contour error of the S1 circle well
// below what backlash and cumulative lead compensation leave (docs/robustness.md "Lead-error table").
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "emulator/scenario_file.hpp"
#include "tools/hil/circle_run.hpp"
#include "tools/hil/gauge_file.hpp"
#include "tools/hil/screw_map_run.hpp"
#include "tests/tune/known_screw.hpp"
#include "tools/tune/screw_fit.hpp"

namespace tnv::hil {
namespace {

using tune::fit_screw;
using tune::ScrewFit;
using tune::to_compensation;

using tune::test::known_error_um;
using tune::test::known_points;

TEST(GaugeFile, RoundTripsAndRefusesBadLinesByNumber) {
  const std::vector<GaugePoint> pts = known_points();
  std::string error;
  const auto back = read_gauge_file(write_gauge_file("x axis\nsecond line", pts), error);
  ASSERT_TRUE(back) << error;
  ASSERT_EQ(back->size(), pts.size());
  EXPECT_NEAR((*back)[5].table_mm, pts[5].table_mm, 1e-6);
  EXPECT_EQ((*back)[100].direction, -1);
  const std::string header = "position_mm,direction,table_mm\n";
  const std::pair<std::string, std::string> bad[] = {
      {"1,1,1\n", "header"},
      {header + "1,1\n", "line 2: expected 3"},
      {header + "1,1,1,1\n", "line 2: expected 3"},
      {header + "1,0,1\n", "direction"},
      {header + "# ok\n1,1,nan\n", "line 3: table_mm"},
      {header + "x,1,1\n", "position_mm"},
      {header, "no measured points"}};
  for (const auto& [text, why] : bad) {
    EXPECT_FALSE(read_gauge_file(text, error)) << text;
    EXPECT_NE(error.find(why), std::string::npos) << error;
  }
}

TEST(ScrewMap, TheMeasuredTableHalvesWhatBacklashAndLeadCompensationLeaveOnTheBench) {
  const emu::Scenario s = *emu::builtin_scenario("bench-no-cut");
  const fw::FirmwareConfig plain = fw::default_firmware_config();
  fw::FirmwareConfig measured = plain;
  for (const hal::Axis axis : {hal::Axis::x, hal::Axis::y}) {
    ScrewMapOptions o;
    o.axis = axis;
    const ScrewMapResult run = run_screw_map(s, plain, o);
    ASSERT_TRUE(run.completed) << run.error;
    std::string error;
    const std::optional<ScrewFit> fit = fit_screw(run.points, 10.0, error);
    ASSERT_TRUE(fit) << error;
    // The bench's screw: 10 um lash (less what the axis settles inside it), +-60 um/m, +-4 um per turn.
    const double lead_um_per_m = axis == hal::Axis::x ? 60.0 : -60.0;
    EXPECT_NEAR(fit->backlash_um, 10.0, 2.0);
    EXPECT_NEAR(fit->lead_um_per_m, lead_um_per_m, 6.0);
    double peak_um = 0.0;
    for (const double e : fit->turn_error_um) peak_um = std::max(peak_um, std::fabs(e));
    EXPECT_NEAR(peak_um, 4.0, 0.5);
    measured.axis[hal::index(axis)].screw = to_compensation(*fit, plain.axis[hal::index(axis)].screw);
  }
  ASSERT_TRUE(fw::validate(measured).ok());
  // What the two scalars alone do (the true values, as if known exactly).
  fw::FirmwareConfig scalars = plain;
  for (fw::AxisConfig& a : scalars.axis) a.screw.backlash_mm = 0.010;
  scalars.axis[0].screw.lead_um_per_m = 60.0;
  scalars.axis[1].screw.lead_um_per_m = -60.0;
  const CircleRunResult with_scalars = run_circle(s, scalars, fw::ControllerKind::rdvsc);
  const CircleRunResult with_table = run_circle(s, measured, fw::ControllerKind::rdvsc);
  ASSERT_TRUE(with_scalars.completed) << with_scalars.error;
  ASSERT_TRUE(with_table.completed) << with_table.error;
  EXPECT_LE(with_table.true_table_stats.mean_um, 0.5 * with_scalars.true_table_stats.mean_um)
      << with_table.true_table_stats.mean_um << " vs " << with_scalars.true_table_stats.mean_um;
  EXPECT_LT(with_table.true_table_stats.max_um, with_scalars.true_table_stats.max_um);
}

}  // namespace
}  // namespace tnv::hil
