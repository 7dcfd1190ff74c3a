// Z in programs on the emulated machine: a plunge, a contour at depth, a
// G2 helix and a retract, read by the G-code reader, run by the firmware
// (R-DVSC+DDC, no cutting) and scored in three dimensions as `tnv-hil
// path` scores them. The tool point's Z follows the program.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <string>

#include "emulator/scenario_file.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tools/hil/path_run.hpp"

namespace tnv::hil {
namespace path_z_test {
namespace {

constexpr std::size_t kZ = hal::index(hal::Axis::z);

// Incremental, so it runs from wherever the machine homes.
constexpr const char* kProgram =
    "G21 G91\n"
    "G1 Z-5 F300\n"              // plunge 5 mm at 5 mm/s
    "G1 X20 F1200\n"             // a contour at depth
    "G1 Y10\n"
    "G1 X-20\n"
    "G2 X0 Y0 Z-2 I0 J-5 F600\n" // one full turn, 2 mm down: a helix
    "G0 Z7\n"                    // retract
    "M2\n";

TEST(PathZ, APlungeAContourAHelixAndARetractFollowInThreeDimensions) {
  const std::optional<emu::Scenario> scenario = emu::builtin_scenario("no-cut");
  ASSERT_TRUE(scenario.has_value());
  PathRunOptions options;
  options.keep_samples = true;
  const PathRunResult r = run_path(*scenario, fw::default_firmware_config(), fw::ControllerKind::rdvsc, kProgram, options);
  ASSERT_TRUE(r.completed) << r.error;
  EXPECT_EQ(r.underruns, 0u);
  EXPECT_EQ(r.guard_failures, 0u);
  EXPECT_LE(r.score.accel_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(r.score.jerk_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(r.score.path_deviation_max_um, 5.0 + 1e-6) << "the path tolerance is 5 um";
  EXPECT_LE(r.score.contour_error_max_um, 6.0) << "the tool point leaves the 3-D path (5.0 um measured)";
  EXPECT_GT(r.score.contour_error_max_um, 0.0);
  // Length: 5 + 20 + 10 + 20 + hypot(2 pi 5, 2) + 7.
  EXPECT_NEAR(r.programmed_length_mm, 62.0 + std::hypot(10.0 * std::numbers::pi, 2.0), 1e-6);
  ASSERT_FALSE(r.samples.empty());
  const double z0 = r.samples.front().reference_mm[kZ];
  double z_min = z0;
  for (const PathSample& s : r.samples) z_min = std::min(z_min, s.position_mm[kZ]);
  EXPECT_NEAR(z_min, z0 - 7.0, 0.01) << "the helix ends 7 mm below the start";
  EXPECT_NEAR(r.samples.back().reference_mm[kZ], z0, 1e-9) << "retracted";
  EXPECT_NEAR(r.samples.back().position_mm[kZ], z0, 0.002);
  std::printf("path z: contour max %.3f um mean %.3f um, path deviation %.3f um, cycle %.3f s, feed ratio %.3f\n",
              r.score.contour_error_max_um, r.score.contour_error_mean_um, r.score.path_deviation_max_um,
              r.score.cycle_time_s, r.score.feed_ratio);
}

TEST(PathZ, ArcsOutsideTheXyPlaneAreRefusedWithTheirLine) {
  const std::optional<emu::Scenario> scenario = emu::builtin_scenario("no-cut");
  ASSERT_TRUE(scenario.has_value());
  const PathRunResult r = run_path(*scenario, fw::default_firmware_config(), fw::ControllerKind::rdvsc,
                                   "G21 G91\nG1 X1 F600\nG18 G2 X2 Z0 I1 K0\nM2\n");
  EXPECT_FALSE(r.completed);
  EXPECT_NE(r.error.find("line 3"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("G18"), std::string::npos) << r.error;
  EXPECT_EQ(r.segments, 0u) << "nothing sent";
}

}  // namespace
}  // namespace path_z_test
}  // namespace tnv::hil
