// Issue 27's contour goal in three dimensions: a helix (G2 with Z) and a
// 3-D contour (arcs in G18 and G19 with the third axis moving, a plunge and
// a retract) at 2 mm/s with R-DVSC+DDC, no cutting, scored as `tnv-hil path
// --seeds 8` scores them: the 3-D contour error's maximum, averaged over 8
// seeded scenarios, at most 5 um; every seed within the axis limits.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdio>
#include <optional>
#include <string>

#include "emulator/scenario_file.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tests/sanitized_build.hpp"
#include "tests/tools/gcode/test_piece_path.hpp"
#include "tools/gcode/program_file.hpp"
#include "tools/hil/path_run.hpp"

namespace tnv::hil {
namespace contour_3d_test {
namespace {

// 8 as the goal states it (about 10 s of CPU for both programs); 2 under a sanitizer.
constexpr int kSeeds = tnv::test::kSanitizedBuild ? 2 : 8;

PathSweepResult run_seeds(const char* name) {
  std::string text, error;
  EXPECT_TRUE(gcode::read_program_file(gcode::test::test_piece_path(name), text, error)) << error;
  const std::optional<emu::Scenario> scenario = emu::builtin_scenario("no-cut");
  EXPECT_TRUE(scenario.has_value());
  if (!scenario) return {};
  return run_path_seeds(*scenario, fw::default_firmware_config(), fw::ControllerKind::rdvsc, text, kSeeds, {});
}

TEST(PathContour3d, AHelixAndA3dContourAtTwoMmPerSecondStayWithinFiveMicrometres) {
  for (const char* name : {"helix_g2_z_2mm_s.ngc", "contour_3d_2mm_s.ngc"}) {
    const PathSweepResult sweep = run_seeds(name);
    ASSERT_EQ(sweep.per_seed.size(), static_cast<std::size_t>(kSeeds)) << name;
    EXPECT_EQ(sweep.error, "") << name;
    EXPECT_EQ(sweep.underruns, 0u) << name;
    for (const PathRunResult& r : sweep.per_seed) {
      EXPECT_TRUE(r.completed) << name << ": " << r.error;
      EXPECT_EQ(r.guard_failures, 0u) << name;
      EXPECT_GT(r.score.contour_error_max_um, 0.0) << name << ": nothing scored";
    }
    EXPECT_LE(sweep.mean.accel_ratio_max, 1.0 + 1e-6) << name << ": commanded acceleration above an axis limit";
    EXPECT_LE(sweep.mean.jerk_ratio_max, 1.0 + 1e-6) << name << ": commanded jerk above an axis limit";
    EXPECT_LE(sweep.mean.path_deviation_max_um, 5.0 + 1e-6) << name << ": the path tolerance is 5 um";
    EXPECT_GE(sweep.mean.feed_ratio, 0.95) << name << ": at 2 mm/s the program runs at its feed";
    if (!tnv::test::kSanitizedBuild) {  // the goal is an 8-seed mean
      EXPECT_LE(sweep.mean.contour_error_max_um, 5.0) << name << ": the goal, 3-D contour error max (8-seed mean)";
    }
    RecordProperty(name, std::to_string(sweep.mean.contour_error_max_um));
    std::printf("[contour 3-D] %s: contour max %.3f um (%d-seed mean), mean %.3f um, path deviation %.3f um, "
                "accel %.3f jerk %.3f, feed ratio %.3f\n",
                name, sweep.mean.contour_error_max_um, kSeeds, sweep.mean.contour_error_mean_um,
                sweep.mean.path_deviation_max_um, sweep.mean.accel_ratio_max, sweep.mean.jerk_ratio_max,
                sweep.mean.feed_ratio);
  }
}

}  // namespace
}  // namespace contour_3d_test
}  // namespace tnv::hil
