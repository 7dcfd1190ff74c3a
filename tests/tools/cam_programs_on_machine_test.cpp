// The oracle's CAM-style programs (tools/gcode/oracle/programs/cam_*.ngc,
// which LinuxCNC's rs274 agrees with call by call) on the emulated machine:
// with a tool table and a G54 that put the work inside Z's travel (the
// drilling program sets its own G55 there with G10 L2) all six run to the
// end within the planner's limits and the path tolerance, the helix one
// with its arcs in G18 and G19, and so does the horizontal spindle's side
// drilling in G18 and G19 (horizontal_spindle_cycles.ngc: on this vertical
// machine its moves only, with no stock; docs/gcode.md "CAM-style programs
// on the emulated machine").
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "emulator/scenario_file.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tools/hil/path_run.hpp"

namespace tnv::hil {
namespace cam_programs_on_machine_test {
namespace {

std::string program_text(const std::string& name) {
  // Appended, not string + literal: GCC 12's false -Warray-bounds on that at -O1.
  std::string path = TNV_SOURCE_DIR;
  path.append("/tools/gcode/oracle/programs/").append(name).append(".ngc");
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Tools 1..10, 41..50 mm long, 6 mm across; G54 150 mm below home at Z's top.
PathRunOptions machine_setup() {
  std::string tools;
  for (int t = 1; t <= 10; ++t)
    tools.append("T").append(std::to_string(t)).append(" P").append(std::to_string(t)).append(" Z")
        .append(std::to_string(40 + t)).append(".0 D6.0\n");
  PathRunOptions options;
  std::string error;
  EXPECT_TRUE(options.canon.tools.load_text(tools, error)) << error;
  EXPECT_TRUE(options.canon.parameters.load_var_text("5221\t0.0\n5222\t0.0\n5223\t-150.0\n", error)) << error;
  return options;
}

PathRunResult run(const std::string& name) {
  const std::optional<emu::Scenario> scenario = emu::builtin_scenario("no-cut");
  EXPECT_TRUE(scenario.has_value());
  const std::string text = program_text(name);
  EXPECT_FALSE(text.empty()) << name;
  return run_path(*scenario, fw::default_firmware_config(), fw::ControllerKind::rdvsc, text, machine_setup());
}

class CamProgramOnMachine : public ::testing::TestWithParam<const char*> {};

TEST_P(CamProgramOnMachine, RunsToTheEndWithinTheLimitsAndThePathTolerance) {
  const PathRunResult r = run(GetParam());
  ASSERT_TRUE(r.completed) << r.error;
  EXPECT_FALSE(r.faulted);
  EXPECT_EQ(r.underruns, 0u);
  EXPECT_EQ(r.guard_failures, 0u);
  EXPECT_GT(r.segments, 10u);
  EXPECT_LE(r.score.accel_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(r.score.jerk_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(r.score.path_deviation_max_um, 5.0 + 1e-6) << "the path tolerance is 5 um";
  // 4.6 to 5.1 um measured (docs/gcode.md): the tool point stays on the 3-D path.
  EXPECT_LE(r.score.contour_error_max_um, 6.0);
  EXPECT_FALSE(r.pauses.empty()) << "every one changes a tool (M6)";
  std::printf("%s: %llu segments, contour max %.2f um, cycle %.2f s\n", GetParam(),
              static_cast<unsigned long long>(r.segments), r.score.contour_error_max_um, r.score.cycle_time_s);
}

INSTANTIATE_TEST_SUITE_P(Oracle, CamProgramOnMachine,
                         ::testing::Values("cam_contour_g54_g43", "cam_contour_g41_g42", "cam_tapping_boring_cycles",
                                           "cam_back_boring_cycles", "cam_drilling_cycles",
                                           "cam_helix_subroutine", "horizontal_spindle_cycles"));

TEST(CamProgramOnMachine, TheDrillingProgramDrillsInItsOwnG55) {
  // Its G10 L2 P2 X100 Y50 Z-150 sets G55: the last hole, G55 X40 Y20, is at machine X140 Y70.
  const std::optional<emu::Scenario> scenario = emu::builtin_scenario("no-cut");
  ASSERT_TRUE(scenario.has_value());
  PathRunOptions options = machine_setup();
  options.keep_samples = true;
  const PathRunResult r = run_path(*scenario, fw::default_firmware_config(), fw::ControllerKind::rdvsc,
                                   program_text("cam_drilling_cycles"), options);
  ASSERT_TRUE(r.completed) << r.error;
  double x_max = -1e9, y_max = -1e9;
  for (const PathSample& s : r.samples) {
    x_max = std::max(x_max, s.reference_mm[0]);
    y_max = std::max(y_max, s.reference_mm[1]);
  }
  EXPECT_NEAR(x_max, 140.0, 1e-6);
  EXPECT_NEAR(y_max, 70.0, 1e-6);
}

}  // namespace
}  // namespace cam_programs_on_machine_test
}  // namespace tnv::hil
