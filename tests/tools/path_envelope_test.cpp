// The per-axis envelope on the emulated machine (docs/motion.md "Per-axis
// envelope"): programs run by the firmware on the emulated table (no
// cutting, R-DVSC+DDC) and scored as `tnv-hil path` scores them. 0.1 mm
// chord circles of radius 5, 10, 20 and 50 mm at 20 mm/s keep feed_ratio >= 0.9;
// at the corners of a square and on an arc the binding axis' commanded
// acceleration reaches 90 % of its limit; no axis ever above its limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "emulator/scenario_file.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tests/sanitized_build.hpp"
#include "tests/tools/gcode/test_piece_path.hpp"
#include "tools/gcode/program_file.hpp"
#include "tools/hil/path_run.hpp"

namespace tnv::hil {
namespace envelope_test {
namespace {

std::string piece(const char* name) {
  std::string text, error;
  EXPECT_TRUE(gcode::read_program_file(gcode::test::test_piece_path(name), text, error)) << error;
  return text;
}

PathRunResult run_on_table(const std::string& gcode) {
  const std::optional<emu::Scenario> scenario = emu::builtin_scenario("no-cut");
  EXPECT_TRUE(scenario.has_value());
  if (!scenario) return {};
  PathRunOptions options;
  options.keep_samples = true;
  PathRunResult r = run_path(*scenario, fw::default_firmware_config(), fw::ControllerKind::rdvsc, gcode, options);
  EXPECT_TRUE(r.completed) << r.error;
  EXPECT_EQ(r.underruns, 0u);
  EXPECT_EQ(r.guard_failures, 0u);
  EXPECT_LE(r.score.accel_ratio_max, 1.0 + 1e-6) << "commanded acceleration above an axis limit";
  EXPECT_LE(r.score.jerk_ratio_max, 1.0 + 1e-6) << "commanded jerk above an axis limit";
  EXPECT_LE(r.score.path_deviation_max_um, 5.0 + 1e-6) << "the path tolerance is 5 um";
  return r;
}

TEST(PathEnvelope, FineChordCirclesKeepNinetyPercentOfTheirFeedOnTheTable) {
  // As programmed: a rapid from the table's home to the circle, then chords
  // at F1200 = 20 mm/s. Issue 27's goal: 0.9 for every radius from 5 mm,
  // the rapid's stop before the first chord (the spindle's feed gate) included.
  // Each radius is judged alone: a sanitizer build runs the two shortest circles.
  std::vector<const char*> names = {"circle_chords_0p1mm_r5.ngc", "circle_chords_0p1mm.ngc"};
  if (!tnv::test::kSanitizedBuild) {
    names.push_back("circle_chords_0p1mm_r20.ngc");
    names.push_back("circle_chords_0p1mm_r50.ngc");
  }
  for (const char* name : names) {
    const PathRunResult run = run_on_table(piece(name));
    EXPECT_GE(run.score.feed_ratio, 0.9) << name;
    EXPECT_LE(run.score.feed_ratio, 1.0 + 1e-9) << name << ": faster than programmed";
    RecordProperty(name, std::to_string(run.score.feed_ratio));
  }
}

// Largest commanded acceleration over its axis limit after the program's
// dwell (the reference at rest for 50 ticks): what follows the rapid.
double accel_ratio_after_dwell(const PathRunResult& r) {
  const fw::motion::MotionLimits limits = fw::path_limits(fw::default_firmware_config());
  const std::vector<PathSample>& s = r.samples;
  std::size_t begin = s.size();
  bool moved = false;  // the rapid first
  for (std::size_t k = 1, still = 0; k < s.size() && begin == s.size(); ++k) {
    const bool same = s[k].reference_mm == s[k - 1].reference_mm;
    moved = moved || !same;
    still = same && moved ? still + 1 : 0;
    if (still >= 50) begin = k;
  }
  EXPECT_LT(begin, s.size()) << "no dwell";
  double worst = 0.0;
  for (std::size_t k = begin + 2; k < s.size(); ++k)
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      const double a = (s[k].reference_mm[i] - 2.0 * s[k - 1].reference_mm[i] + s[k - 2].reference_mm[i]) / 1e-6;
      worst = std::max(worst, std::fabs(a) / limits.axis[i].accel_mm_s2);
    }
  return worst;
}

TEST(PathEnvelope, TheBindingAxisReachesNinetyPercentAtCornersAndOnAnArcOnTheTable) {
  // A square at 50 mm/s after a dwell: the lines brake into and leave every corner.
  const PathRunResult square = run_on_table("G17 G21 G90\nG0 X0 Y0\nG4 P0.1\nG1 F3000 X20\nY20\nX0\nY0\nM2\n");
  const double at_corners = accel_ratio_after_dwell(square);
  EXPECT_GE(at_corners, 0.9);
  // A full circle of r 10 at 30 mm/s from rest on its start: every sample after the dwell is on the arc.
  const PathRunResult arc = run_on_table("G17 G21 G90\nG0 X10 Y0\nG4 P0.1\nG3 F1800 X10 Y0 I-10 J0\nM2\n");
  const double on_arc = accel_ratio_after_dwell(arc);
  EXPECT_GE(on_arc, 0.9);
  RecordProperty("square_accel_ratio", std::to_string(at_corners));
  RecordProperty("arc_accel_ratio", std::to_string(on_arc));
}

}  // namespace
}  // namespace envelope_test
}  // namespace tnv::hil
