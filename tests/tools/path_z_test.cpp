// Z in programs on the emulated machine: a plunge, a contour at depth, a
// G2 helix and a retract, read by the G-code reader, run by the firmware
// (R-DVSC+DDC, no cutting) and scored in three dimensions as `tnv-hil
// path` scores them. The tool point's Z follows the program; arcs in G18
// and G19 run in their planes.
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

// Arcs in G18 and G19 (helices along Y and X), a P2 helix in G18 among
// them, run end to end and scored in three dimensions against their planes.
constexpr const char* kPlanesProgram =
    "G21 G91\n"
    "G1 Z-10 F300\n"                       // plunge
    "G18 G2 X10 Z0 I5 K0 Y-2 F600\n"       // a half turn in ZX dipping 5 mm, Y 2 mm along
    "G19 G3 Y10 Z0 J5 K0 X2\n"             // a half turn in YZ dipping 5 mm, X 2 mm along
    "G18 G3 X0 Z0 I0 K-3 Y3 P2\n"          // two full turns in ZX below, Y 3 mm along
    "G17 G0 Z10\n"                         // retract
    "M2\n";

TEST(PathZ, ArcsInG18AndG19RunInTheirPlanesAndScoreInThreeDimensions) {
  const std::optional<emu::Scenario> scenario = emu::builtin_scenario("no-cut");
  ASSERT_TRUE(scenario.has_value());
  PathRunOptions options;
  options.keep_samples = true;
  const PathRunResult r =
      run_path(*scenario, fw::default_firmware_config(), fw::ControllerKind::rdvsc, kPlanesProgram, options);
  ASSERT_TRUE(r.completed) << r.error;
  EXPECT_FALSE(r.faulted);
  EXPECT_EQ(r.segments, 6u) << "plunge, two half turns, the P2 helix as two turns, retract";
  EXPECT_EQ(r.underruns, 0u);
  EXPECT_EQ(r.guard_failures, 0u);
  EXPECT_LE(r.score.accel_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(r.score.jerk_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(r.score.path_deviation_max_um, 5.0 + 1e-6) << "the path tolerance is 5 um";
  EXPECT_GT(r.score.contour_error_max_um, 0.0);
  EXPECT_LE(r.score.contour_error_max_um, 6.0);
  // 10 + hypot(5 pi, 2) + hypot(5 pi, 2) + hypot(2 * 6 pi, 3) + 10.
  EXPECT_NEAR(r.programmed_length_mm,
              20.0 + 2.0 * std::hypot(5.0 * std::numbers::pi, 2.0) + std::hypot(12.0 * std::numbers::pi, 3.0), 1e-6);
  ASSERT_FALSE(r.samples.empty());
  const double z0 = r.samples.front().reference_mm[kZ];
  double z_min = z0;
  for (const PathSample& s : r.samples) z_min = std::min(z_min, s.reference_mm[kZ]);
  EXPECT_NEAR(z_min, z0 - 16.0, 1e-3) << "the full turns reach 6 mm below the plunge";
  EXPECT_NEAR(r.samples.back().reference_mm[kZ], z0, 1e-9) << "retracted";
  std::printf("path G18/G19: contour max %.3f um mean %.3f um, path deviation %.3f um, accel %.3f jerk %.3f, "
              "cycle %.3f s\n",
              r.score.contour_error_max_um, r.score.contour_error_mean_um, r.score.path_deviation_max_um,
              r.score.accel_ratio_max, r.score.jerk_ratio_max, r.score.cycle_time_s);
}

}  // namespace
}  // namespace path_z_test
}  // namespace tnv::hil
