// tnv-hil path's run from line N (the interpreter's RunFromLine with the
// machine where the table stands): the start's approach and the rest of
// the program run on the emulated table, and the run ends where the full
// run ends; the lines before N move nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "emulator/scenario_file.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tools/hil/path_run.hpp"

namespace tnv::hil {
namespace {

// Incremental moves, a spindle and a loop: line 7 is the second pass's first line.
const std::string kProgram =
    "G21 G91 G17 F600\n"        // 1
    "S3000 M3\n"                // 2
    "G1 X4\n"                   // 3
    "#1 = 0\n"                  // 4
    "o1 while [#1 LT 2]\n"      // 5
    "  G1 Y2\n"                 // 6
    "  G2 X2 Y2 I2 J0\n"        // 7
    "  #1 = [#1 + 1]\n"         // 8
    "o1 endwhile\n"             // 9
    "G1 X-3 Y-1\n"              // 10
    "M2\n";

PathRunResult run(const std::optional<gcode::RunFromLine>& from) {
  const std::optional<emu::Scenario> scenario = emu::builtin_scenario("no-cut");
  EXPECT_TRUE(scenario.has_value());
  if (!scenario) return {};
  PathRunOptions options;
  options.keep_samples = true;
  options.canon.from_line = from;
  return run_path(*scenario, fw::default_firmware_config(), fw::ControllerKind::rdvsc, kProgram, options);
}

TEST(PathFromLine, ARunFromLineEndsWhereTheFullRunEnds) {
  const PathRunResult full = run(std::nullopt);
  ASSERT_TRUE(full.completed) << full.error;
  ASSERT_FALSE(full.samples.empty());
  gcode::RunFromLine from;
  from.line = 6;
  from.pass = 2;  // the loop's second pass
  // The clearance where the machine stands: no retract and no descent, the XY lengths compare.
  from.clearance_z_mm = full.samples.front().reference_mm[hal::index(hal::Axis::z)];
  const PathRunResult part = run(from);
  ASSERT_TRUE(part.completed) << part.error;
  ASSERT_FALSE(full.samples.empty());
  ASSERT_FALSE(part.samples.empty());
  const PathSample& a = full.samples.back();
  const PathSample& b = part.samples.back();
  EXPECT_LT(std::hypot(a.reference_mm[0] - b.reference_mm[0], a.reference_mm[1] - b.reference_mm[1]), 1e-6)
      << "full run ends at (" << a.reference_mm[0] << ", " << a.reference_mm[1] << "), from line 6 pass 2 at ("
      << b.reference_mm[0] << ", " << b.reference_mm[1] << ")";
  EXPECT_LT(std::hypot(a.position_mm[0] - b.position_mm[0], a.position_mm[1] - b.position_mm[1]), 1e-3);
  // Shorter: the first pass and the first line were not run, only approached past.
  EXPECT_LT(part.programmed_length_mm, full.programmed_length_mm);
  // The spindle of line 2 is in force at line 6: started before the approach's feed.
  bool started = false;
  for (const fw::motion::Segment& s : part.program.segments)
    if (s.spindle == fw::motion::SpindleChange::forward && s.spindle_rpm == 3000.0) started = true;
  EXPECT_TRUE(started) << "the run from line 6 does not start the spindle line 2 started";
  // No element of a line before 6 in the run itself (the approach's calls carry line 6).
  for (const fw::motion::Segment& s : part.program.segments) {
    EXPECT_GE(s.tag, 6u) << "an element of line " << s.tag;
  }
}

}  // namespace
}  // namespace tnv::hil
