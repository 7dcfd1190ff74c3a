// G87 (back boring), G88 (bore, spindle stopped, program stop: the
// operator retracts by hand) and canned cycles in G18 (along Y) and G19
// (along X). Each expected call sequence is what LinuxCNC's rs274 prints
// for the same program; the oracle compares the two on random runs
// (docs/gcode.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "tests/tools/gcode/canon_test_support.hpp"
#include "tools/gcode/canon_interpreter.hpp"

namespace tnv::gcode {
namespace back_boring_test {

CanonSetup one_tool() { return test::setup_with_tools("T1 P1 Z10 D6\n"); }

std::string traverse(const char* xyz) { return std::string("STRAIGHT_TRAVERSE(") + xyz + ", 0.0000, 0.0000, 0.0000)"; }
std::string feed(const char* xyz) { return std::string("STRAIGHT_FEED(") + xyz + ", 0.0000, 0.0000, 0.0000)"; }

// The calls after the first `skip` of the program's own.
std::vector<std::string> calls_after(const std::string& text, std::size_t skip) {
  const std::vector<std::string> all = test::calls_between_start_and_end(text, one_tool());
  return all.size() > skip ? std::vector<std::string>(all.begin() + static_cast<long>(skip), all.end())
                           : std::vector<std::string>{};
}

TEST(BackBoring, G87GoesThroughTheHoleAtTheOffsetOrientedAndBoresUpward) {
  // M4: the spindle restarts counterclockwise; ORIENT_SPINDLE's 3 is that direction.
  EXPECT_EQ(calls_after("G21 G17 G90 F100 S1000 M4\nG0 X0 Y0 Z5\nG98 G87 X10 Y5 Z-8 R1 I2 J-1 K-5\nM2\n", 7),
            (std::vector<std::string>{
                "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)", traverse("10.0000, 5.0000, 5.0000"),
                traverse("10.0000, 5.0000, 1.0000"), traverse("12.0000, 4.0000, 1.0000"), "STOP_SPINDLE_TURNING(0)",
                "ORIENT_SPINDLE(0, 0.0000, 3)", traverse("12.0000, 4.0000, -8.0000"),
                traverse("10.0000, 5.0000, -8.0000"), "START_SPINDLE_COUNTERCLOCKWISE(0)",
                feed("10.0000, 5.0000, -5.0000"), feed("10.0000, 5.0000, -8.0000"), "STOP_SPINDLE_TURNING(0)",
                "ORIENT_SPINDLE(0, 0.0000, 3)", traverse("12.0000, 4.0000, -8.0000"),
                traverse("12.0000, 4.0000, 5.0000"), traverse("10.0000, 5.0000, 5.0000"),
                "START_SPINDLE_COUNTERCLOCKWISE(0)", "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.000000)",
                "SET_NAIVECAM_TOLERANCE(0.0000)"}));
}

TEST(BackBoring, G88StopsTheProgramAtTheBottomAndTheToolIsTakenToBeAtTheClearance) {
  // After the stop the interpreter takes the tool to be at R (G99); the
  // machine's last point is the bottom, where a tool change takes the
  // position back from: the next move starts at Z-3.
  EXPECT_EQ(calls_after("G21 G17 G90 F100 S1000 M3\nG0 X0 Y0 Z5\nG99 G88 X10 Y5 Z-3 R1 P0.5\nT1 M6\nG0 X3\nM2\n", 7),
            (std::vector<std::string>{
                "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)", traverse("10.0000, 5.0000, 5.0000"),
                traverse("10.0000, 5.0000, 1.0000"), feed("10.0000, 5.0000, -3.0000"), "DWELL(0.5000)",
                "STOP_SPINDLE_TURNING(0)", "PROGRAM_STOP()", "START_SPINDLE_CLOCKWISE(0)",
                "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.000000)", "SET_NAIVECAM_TOLERANCE(0.0000)",
                "SELECT_TOOL(1)", "START_CHANGE()", "STOP_SPINDLE_TURNING(0)", "CHANGE_TOOL(1)",
                traverse("3.0000, 5.0000, -3.0000")}));
  // Without the tool change the next hole is reached from R, not the bottom.
  const auto all = calls_after("G21 F100 S1000 M3\nG0 Z5\nG99 G88 X10 Y5 Z-3 R1 P0.5\nX20\nM2\n", 0);
  const auto second = std::find(std::find(all.begin(), all.end(), "PROGRAM_STOP()"), all.end(),
                                "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)");
  ASSERT_TRUE(second != all.end() && second + 1 != all.end());
  EXPECT_EQ(*(second + 1), traverse("20.0000, 5.0000, 1.0000"));
}

TEST(BackBoring, CyclesInG18DrillAlongYAndInG19AlongX) {
  // G19 G91 continues the run that began in G18 at Y5: R counts from that
  // 5 along X now (one number, as rs274 keeps it), and rises to it first.
  EXPECT_EQ(calls_after("G21 G90 F100\nG0 X1 Y5 Z2\nG18 G99 G81 X10 Z5 Y-3 R1\nG19 G91 G98 G81 Y2 Z1 X-4 R1\nG17\nM2\n", 3),
            (std::vector<std::string>{
                "SELECT_PLANE(CANON_PLANE_XZ)", "COMMENT(\"interpreter: retract mode set to r_plane\")",
                "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)", traverse("10.0000, 5.0000, 5.0000"),
                traverse("10.0000, 1.0000, 5.0000"), feed("10.0000, -3.0000, 5.0000"),
                traverse("10.0000, 1.0000, 5.0000"), "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.000000)",
                "SET_NAIVECAM_TOLERANCE(0.0000)", "SELECT_PLANE(CANON_PLANE_YZ)",
                "COMMENT(\"interpreter: distance mode changed to incremental\")",
                "COMMENT(\"interpreter: retract mode set to old_z\")", traverse("6.0000, 1.0000, 5.0000"),
                "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)", traverse("6.0000, 3.0000, 6.0000"),
                feed("2.0000, 3.0000, 6.0000"), traverse("6.0000, 3.0000, 6.0000"),
                "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.000000)", "SET_NAIVECAM_TOLERANCE(0.0000)",
                "SELECT_PLANE(CANON_PLANE_XY)"}));
}

TEST(BackBoring, RefusalsNameTheMissingWordOrTheSpindle) {
  // Each of these but the G84 rs274 refuses too (the oracle test compares them).
  GcodeError e = test::refusal_of("F100 S100 M3\nG87 X1 Y1 Z-5 R1 I1 J1\nM2\n", one_tool());
  EXPECT_EQ(e.line, 2);
  EXPECT_NE(e.message.find("G87 needs K"), std::string::npos) << e.message;
  e = test::refusal_of("F100 S100 M3\nG88 X1 Y1 Z-5 R1\nM2\n", one_tool());
  EXPECT_NE(e.message.find("G88 needs P"), std::string::npos) << e.message;
  e = test::refusal_of("F100\nG88 X1 Y1 Z-5 R1 P1\nM2\n", one_tool());
  EXPECT_NE(e.message.find("G88 with the spindle stopped"), std::string::npos) << e.message;
  e = test::refusal_of("F100 S100 M4\nG87 X1 Y1 Z-5 R1 I1 J1 K-2\nG88 X2\nM2\n", one_tool());
  EXPECT_EQ(e.line, 3);  // a new cycle names its words again
  e = test::refusal_of("F100\nG18 G81 X1 Z1 R1\nM2\n", one_tool());
  EXPECT_NE(e.message.find("G81 needs Y"), std::string::npos) << e.message;
  e = test::refusal_of("F100\nG19 G81 Y1 Z1 X2 R1\nM2\n", one_tool());
  EXPECT_NE(e.message.find("R below the bottom X"), std::string::npos) << e.message;
  // rs274 runs this one, tapping along permuted axes (docs/gcode.md, deviations): refused here.
  e = test::refusal_of("F100 S100 M3\nG18 G84 X10 Z5 Y-3 R1\nM2\n", one_tool());
  EXPECT_NE(e.message.find("G84 only in the XY plane"), std::string::npos) << e.message;
  e = test::refusal_of("F100\nG18 G81 @5 ^30 Y-3 R1\nM2\n", one_tool());
  EXPECT_NE(e.message.find("polar"), std::string::npos) << e.message;
}

}  // namespace back_boring_test
}  // namespace tnv::gcode
