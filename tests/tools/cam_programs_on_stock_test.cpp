// The oracle's CAM-style programs cutting a stock on the emulated machine
// (docs/gcode.md "CAM-style programs on a stock"): each with the block of
// tests/data/stock/<program>.toml where its G54 (or its own G55) puts the
// part, the top at its Z0, and the tool table and .var file beside them.
// All six run to the end there (the two contours, the drilling, the tapping
// and boring and the back boring in the holes their parts come with, and
// the helical pockets) with no crash and no feed move started before the
// spindle was at speed, judged from the machine's truth, within the
// planner's limits; the shortest also through tnv-hil path, as the docs
// give the command. horizontal_spindle_cycles.ngc (a horizontal spindle's
// side holes) is the oracle's only: this machine's spindle is vertical.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "emulator/scenario_file.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tests/tools/cli_runner.hpp"
#include "tools/hil/path_run.hpp"

namespace tnv::hil {
namespace cam_programs_on_stock_test {
namespace {

std::string source_path(const char* relative) {
  // Appended, not string + literal: GCC 12's false -Warray-bounds on that at -O1.
  std::string path = TNV_SOURCE_DIR;
  path.append("/").append(relative);
  return path;
}

std::string program_path(const std::string& name) {
  return source_path("tools/gcode/oracle/programs/").append(name).append(".ngc");
}

std::string stock_path(const std::string& file) { return source_path("tests/data/stock/").append(file); }

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

PathRunResult run_on_stock(const std::string& name) {
  const emu::ScenarioResult scenario = emu::load_scenario_file(stock_path(name + ".toml"));
  EXPECT_TRUE(scenario.scenario.has_value()) << scenario.error;
  EXPECT_TRUE(scenario.scenario->stock.enabled);
  PathRunOptions options;
  std::string error;
  EXPECT_TRUE(options.canon.tools.load_text(read_text(stock_path("cam_tools.tbl")), error)) << error;
  EXPECT_TRUE(options.canon.parameters.load_var_text(read_text(stock_path("cam_g54.var")), error)) << error;
  const std::string text = read_text(program_path(name));
  EXPECT_FALSE(text.empty()) << name;
  return run_path(*scenario.scenario, fw::default_firmware_config(), fw::ControllerKind::rdvsc, text, options);
}

struct OnStock {
  const char* program;
  double force_min_n;  // the block is under the cuts, not beside them (the force is in XY: a drill's is ~0)
};

void PrintTo(const OnStock& s, std::ostream* os) { *os << s.program; }

class CamProgramOnStock : public ::testing::TestWithParam<OnStock> {};

TEST_P(CamProgramOnStock, CutsToTheEndWithNoCrashAndNoFeedBeforeTheSpindleIsAtSpeed) {
  const PathRunResult r = run_on_stock(GetParam().program);
  ASSERT_TRUE(r.completed) << r.error;
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_FALSE(r.faulted);
  EXPECT_EQ(r.crashes, 0u);
  EXPECT_EQ(r.feed_before_at_speed, 0u);
  EXPECT_GE(r.feed_onsets, 2u) << "every one starts feeds from rest (plunges, corners, holes)";
  EXPECT_EQ(r.underruns, 0u);
  EXPECT_LE(r.score.accel_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(r.score.jerk_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(r.score.path_deviation_max_um, 5.0 + 1e-6) << "the path tolerance is 5 um";
  EXPECT_LE(r.score.contour_error_max_um, 6.0);
  EXPECT_GE(r.tool_force_max_n, GetParam().force_min_n);
  std::printf("%s on its stock: %u feed starts, force max %.0f N, contour max %.2f um, cycle %.2f s\n", GetParam().program,
              r.feed_onsets, r.tool_force_max_n, r.score.contour_error_max_um, r.score.cycle_time_s);
}

INSTANTIATE_TEST_SUITE_P(Oracle, CamProgramOnStock,
                         ::testing::Values(OnStock{"cam_contour_g54_g43", 100.0},
                                           OnStock{"cam_contour_g41_g42", 100.0},
                                           OnStock{"cam_drilling_cycles", 0.0},
                                           // taps and bars in the part's own holes ([[stock.hole]]): nothing in XY
                                           OnStock{"cam_tapping_boring_cycles", 0.0},
                                           // the bar goes down and back bores in holes wider than its reach
                                           OnStock{"cam_back_boring_cycles", 0.0},
                                           // each helix turn meets the last turn's floor
                                           OnStock{"cam_helix_subroutine", 100.0}),
                         [](const ::testing::TestParamInfo<OnStock>& p) { return std::string(p.param.program); });

TEST(CamProgramOnStock, TheDocumentedCommandLineReportsNoCrash) {
  const test::CliRun r = test::run_tnv_hil(
      "path " + program_path("cam_contour_g54_g43") + " --scenario " + stock_path("cam_contour_g54_g43.toml") +
      " --tool-table " + stock_path("cam_tools.tbl") + " --var-file " + stock_path("cam_g54.var") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["crashes"].get<int>(), 0);
  EXPECT_EQ(j["feed_before_at_speed"].get<int>(), 0);
  EXPECT_GE(j["feed_onsets"].get<int>(), 2);
}

}  // namespace
}  // namespace cam_programs_on_stock_test
}  // namespace tnv::hil
