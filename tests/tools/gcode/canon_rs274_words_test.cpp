// Polar words in canned cycles, G5.1 splines, G38.2-G38.5 probing, the
// (LOG...) comments and M70-M73 modal state in the LinuxCNC-dialect
// interpreter. Each expected call is what LinuxCNC's rs274 prints for the
// same program (the oracle test compares the samples hole-circle, polar,
// systems, gridprobe, smartprobe and toplevel with it call by call); each
// refusal names its line and column and returns no call.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "tests/tools/gcode/canon_test_support.hpp"
#include "tools/gcode/canon_interpreter.hpp"

namespace tnv::gcode {
namespace rs274_words_test {

CanonSetup tools_setup() { return test::setup_with_tools("T1 P1 Z2.5 D1.25\n"); }

std::vector<std::string> moves_of(const std::string& text) {
  return test::calls_between_start_and_end(text, tools_setup());
}

GcodeError error_of(const std::string& text) { return test::refusal_of(text, tools_setup()); }

std::string at(double x, double y, double z) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.4f, %.4f, %.4f, 0.0000, 0.0000, 0.0000", x, y, z);
  return buf;
}

TEST(CanonRs274Words, PolarWordsInCannedCycles) {
  // G91: each repeat adds ^90 to the last hole's angle about the origin;
  // G90: one hole at @5 (angle from here), then ^180 (radius from here).
  const auto c = moves_of("G0 X15 Y0 Z0\nG91 G81 R1 Z-5 ^90 L2 F10\nG90 G81 @5 R2 Z-1\n^180\nM2\n");
  const std::vector<std::string> expected = {
      "STRAIGHT_TRAVERSE(" + at(15, 0, 0) + ")", "SET_FEED_RATE(10.0000)",
      "COMMENT(\"interpreter: distance mode changed to incremental\")", "STRAIGHT_TRAVERSE(" + at(15, 0, 1) + ")",
      "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)", "STRAIGHT_TRAVERSE(" + at(0, 15, 1) + ")",
      "STRAIGHT_FEED(" + at(0, 15, -4) + ")", "STRAIGHT_TRAVERSE(" + at(0, 15, 1) + ")",
      "STRAIGHT_TRAVERSE(" + at(-15, 0, 1) + ")", "STRAIGHT_FEED(" + at(-15, 0, -4) + ")",
      "STRAIGHT_TRAVERSE(" + at(-15, 0, 1) + ")", "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.000000)",
      "SET_NAIVECAM_TOLERANCE(0.0000)", "COMMENT(\"interpreter: distance mode changed to absolute\")",
      "STRAIGHT_TRAVERSE(" + at(-15, 0, 2) + ")", "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)",
      "STRAIGHT_TRAVERSE(" + at(-5, 0, 2) + ")", "STRAIGHT_FEED(" + at(-5, 0, -1) + ")",
      "STRAIGHT_TRAVERSE(" + at(-5, 0, 2) + ")", "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.000000)",
      "SET_NAIVECAM_TOLERANCE(0.0000)", "STRAIGHT_TRAVERSE(" + at(-5, 0, 2) + ")",
      "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)", "STRAIGHT_TRAVERSE(" + at(-5, 0, 2) + ")",
      "STRAIGHT_FEED(" + at(-5, 0, -1) + ")", "STRAIGHT_TRAVERSE(" + at(-5, 0, 2) + ")",
      "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.000000)", "SET_NAIVECAM_TOLERANCE(0.0000)"};
  EXPECT_EQ(c, expected);
  const GcodeError e = error_of("F10\nG81 X1 ^30 R1 Z-1\nM2\n");  // polar and X on one line
  EXPECT_EQ(e.line, 2);
  EXPECT_EQ(e.column, 8);
  EXPECT_NE(e.message.find("polar"), std::string::npos) << e.message;
}

TEST(CanonRs274Words, QuadraticSplineG51) {
  // rs274 prints the spline without its points; the end point is where the
  // next move starts, and G5.1 leaves the motion mode (G1 here) as it was.
  EXPECT_EQ(moves_of("G1 X0 Y0 Z0 F100\nG5.1 X10 Y10 I5 J1\nX5\nG91 G5.1 ^90 I1 J1\nG0 Z1\nM2\n"),
            (std::vector<std::string>{"SET_FEED_RATE(100.0000)", "STRAIGHT_FEED(" + at(0, 0, 0) + ")",
                                      "NURBS_FEED(3, ...)", "STRAIGHT_FEED(" + at(5, 10, 0) + ")",
                                      "COMMENT(\"interpreter: distance mode changed to incremental\")",
                                      "NURBS_FEED(3, ...)", "STRAIGHT_TRAVERSE(" + at(-10, 5, 1) + ")"}));
  // rs274's canon is left at X0 Y0 by a spline: a tool change takes the
  // position back from there, and a probe backs off toward it.
  EXPECT_EQ(moves_of("F10 G0 X5 Y5 Z3\nG5.1 X10 Y0 I1 J1\nT1 M6\nG1 Z1\nG5.1 X10 Y0 I1 J1\nG38.3 Z-10\nG1 Z0\nM2\n"),
            (std::vector<std::string>{"SET_FEED_RATE(10.0000)", "STRAIGHT_TRAVERSE(" + at(5, 5, 3) + ")",
                                      "NURBS_FEED(3, ...)", "SELECT_TOOL(1)", "START_CHANGE()",
                                      "STOP_SPINDLE_TURNING(0)", "CHANGE_TOOL(1)", "STRAIGHT_FEED(" + at(0, 0, 1) + ")",
                                      "NURBS_FEED(3, ...)", "TURN_PROBE_ON()", "STRAIGHT_PROBE(" + at(10, 0, -10) + ")",
                                      "TURN_PROBE_OFF()", "STRAIGHT_FEED(" + at(9.8291, 0, 0) + ")"}));
  struct Bad {
    const char* text;
    int line, column;
    const char* says;
  };
  for (const Bad& b : {Bad{"F10\nG5.1 X1 Y1 I1\nM2\n", 2, 12, "both I and J"},
                       Bad{"F10\nG5.1 X1 Y1 Z0 I1 J1\nM2\n", 2, 12, "Z"},
                       Bad{"F10\nG5.1 I1 J1\nM2\n", 2, 1, "end point"},
                       Bad{"F10 G18\nG5.1 X1 I1 J1\nM2\n", 2, 1, "XY plane"},
                       Bad{"G5.1 X1 Y1 I1 J1\nM2\n", 1, 1, "zero feed rate"},
                       Bad{"F10\nG41.1 D1\nG5.1 X1 Y1 I1 J1\nM2\n", 3, 1, "compensation"},
                       Bad{"F10\nG5.1 X1 Y1 I1 J1 P2\nM2\n", 2, 18, "word P"}}) {
    const GcodeError e = error_of(b.text);
    EXPECT_EQ(e.line, b.line) << b.text;
    EXPECT_EQ(e.column, b.column) << b.text << e.message;
    EXPECT_NE(e.message.find(b.says), std::string::npos) << b.text << e.message;
  }
}

TEST(CanonRs274Words, ProbingAsTheStandaloneRs274ModelsIt) {
  // No probe input: each probe move reaches its end, the position backs off
  // 0.254 mm toward the start, #5061-#5063 hold the end and #5070 is 0.
  EXPECT_EQ(moves_of("F100 G0 X0 Y0 Z0\nG38.2 Z-10\n(DEBUG,#5061 #5062 #5063 #5070)\nG1 X1\nG38.3 X5\n"
                     "G38.4 X1 Y2\nG38.5 Z1\nG0 X0\nM2\n"),
            (std::vector<std::string>{
                "SET_FEED_RATE(100.0000)", "STRAIGHT_TRAVERSE(" + at(0, 0, 0) + ")", "TURN_PROBE_ON()",
                "STRAIGHT_PROBE(" + at(0, 0, -10) + ")", "TURN_PROBE_OFF()",
                "MESSAGE(\"0.000000 0.000000 -10.000000 0.000000\")", "STRAIGHT_FEED(" + at(1, 0, -9.746) + ")",
                "TURN_PROBE_ON()", "STRAIGHT_PROBE(" + at(5, 0, -9.746) + ")", "TURN_PROBE_OFF()", "TURN_PROBE_ON()",
                "STRAIGHT_PROBE(" + at(1, 2, -9.746) + ")", "TURN_PROBE_OFF()", "TURN_PROBE_ON()",
                "STRAIGHT_PROBE(" + at(1.2241, 1.8804, 1) + ")", "TURN_PROBE_OFF()",
                "STRAIGHT_TRAVERSE(" + at(0, 1.8804, 0.746) + ")"}));
  // In inches the back-off is 0.010 inch and #5061 stays in inches.
  EXPECT_EQ(moves_of("G20 F10 G0 X0 Y0 Z0\nG38.5 X10\n(DEBUG,#5061)\nG0 Y0\nM2\n"),
            (std::vector<std::string>{"SET_FEED_RATE(10.0000)", "USE_LENGTH_UNITS(CANON_UNITS_INCHES)",
                                      "STRAIGHT_TRAVERSE(" + at(0, 0, 0) + ")", "TURN_PROBE_ON()",
                                      "STRAIGHT_PROBE(" + at(10, 0, 0) + ")", "TURN_PROBE_OFF()",
                                      "MESSAGE(\"10.000000\")", "STRAIGHT_TRAVERSE(" + at(9.99, 0, 0) + ")"}));
  struct Bad {
    const char* text;
    int line, column;
    const char* says;
  };
  // G38.3/G38.5 (no error when the probe does not change) may stay where they are.
  EXPECT_EQ(moves_of("F10\nG38.5 X0\nG38.3 Y0\nG0 X1\nM2\n"),
            (std::vector<std::string>{"SET_FEED_RATE(10.0000)", "TURN_PROBE_ON()", "STRAIGHT_PROBE(" + at(0, 0, 0) + ")",
                                      "TURN_PROBE_OFF()", "TURN_PROBE_ON()", "STRAIGHT_PROBE(" + at(0, 0, 0) + ")",
                                      "TURN_PROBE_OFF()", "STRAIGHT_TRAVERSE(" + at(1, 0, 0) + ")"}));
  for (const Bad& b : {Bad{"F10\nG38.2 X0\nM2\n", 2, 1, "zero length"}, Bad{"F10\nG38.4 Y0\nM2\n", 2, 1, "zero length"},
                       Bad{"G38.2 X1\nM2\n", 1, 1, "zero feed rate"},
                       Bad{"F10\nG38.2\nM2\n", 2, 1, "axis word"},
                       Bad{"F10\nG41.1 D1\nG38.2 Z-1\nM2\n", 3, 1, "compensation"},
                       Bad{"F10\nG38.2 Z-1 M2\n", 2, 11, "one line"}}) {
    const GcodeError e = error_of(b.text);
    EXPECT_EQ(e.line, b.line) << b.text;
    EXPECT_EQ(e.column, b.column) << b.text << e.message;
    EXPECT_NE(e.message.find(b.says), std::string::npos) << b.text << e.message;
  }
}

TEST(CanonRs274Words, LogCommentsAreCallsNotFiles) {
  EXPECT_EQ(moves_of("(LOGOPEN,p.txt)\n#1=2\n(LOG,x=#1)\n(LOGAPPEND,q.txt)\n(LOGCLOSE)\n(LOG)\nM2\n"),
            (std::vector<std::string>{"LOGOPEN(\"p.txt\")", "LOG(\"x=2.000000\")", "LOGAPPEND(\"q.txt\")",
                                      "LOGCLOSE()", "COMMENT(\"LOG\")"}));
}

TEST(CanonRs274Words, ModalStateSaveAndRestore) {
  // M72 runs the saved modes that differ: F S M3-M5 M9 plane G54.. G61/G64
  // G90/G91 G98/G99 as one line, M8 after them; M71 forgets the state.
  const auto c = moves_of("F200 S1200 M8\nG90 G64 P0.1\nM70 (save)\nF50 S120 M3 M9 G91 G18 G61 G55 G98\nG1 X5\n"
                          "M72\nG0 X1\nM71\nM2\n");
  const std::vector<std::string> expected = {
      "SET_FEED_RATE(200.0000)", "SET_SPINDLE_SPEED(0, 1200.0000)", "FLOOD_ON()",
      "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.100000)", "SET_NAIVECAM_TOLERANCE(0.1000)", "COMMENT(\"save\")",
      "SET_FEED_RATE(50.0000)", "SET_SPINDLE_SPEED(0, 120.0000)", "START_SPINDLE_CLOCKWISE(0)", "MIST_OFF()",
      "FLOOD_OFF()", "SELECT_PLANE(CANON_PLANE_XZ)",
      "SET_G5X_OFFSET(2, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
      "SET_G92_OFFSET(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)", "SET_XY_ROTATION(0.0000)",
      "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)", "COMMENT(\"interpreter: distance mode changed to incremental\")",
      "COMMENT(\"interpreter: retract mode set to old_z\")", "STRAIGHT_FEED(" + at(5, 0, 0) + ")",
      // M72
      "SET_FEED_RATE(200.0000)", "SET_SPINDLE_SPEED(0, 1200.0000)", "STOP_SPINDLE_TURNING(0)",
      "SELECT_PLANE(CANON_PLANE_XY)", "SET_G5X_OFFSET(1, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
      "SET_G92_OFFSET(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)", "SET_XY_ROTATION(0.0000)",
      "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.100000)", "SET_NAIVECAM_TOLERANCE(0.1000)",
      "COMMENT(\"interpreter: distance mode changed to absolute\")",
      "COMMENT(\"interpreter: retract mode set to r_plane\")", "FLOOD_ON()", "STRAIGHT_TRAVERSE(" + at(1, 0, 0) + ")"};
  EXPECT_EQ(c, expected);
  // M73 in a subroutine: restored on its endsub line.
  EXPECT_EQ(moves_of("o1 sub\nM73\nF6 G91 M7\no1 endsub\nF1\no1 call\nG0 X1\nM2\n"),
            (std::vector<std::string>{"SET_FEED_RATE(1.0000)", "SET_FEED_RATE(6.0000)", "MIST_ON()",
                                      "COMMENT(\"interpreter: distance mode changed to incremental\")",
                                      "SET_FEED_RATE(1.0000)", "MIST_OFF()", "FLOOD_OFF()",
                                      "COMMENT(\"interpreter: distance mode changed to absolute\")",
                                      "STRAIGHT_TRAVERSE(" + at(1, 0, 0) + ")"}));
  // A tool length offset: G43 restored with the tool in the spindle.
  EXPECT_EQ(moves_of("T1 M6 G43\nM70\nG49\nM72\nM2\n"),
            (std::vector<std::string>{
                "SELECT_TOOL(1)", "START_CHANGE()", "STOP_SPINDLE_TURNING(0)", "CHANGE_TOOL(1)",
                "USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 2.5000, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)",
                "USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)",
                "USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 2.5000, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)"}));
  // M71 only forgets: allowed while compensating, as in rs274.
  EXPECT_EQ(moves_of("F10\nG41.1 D1\nG1 X5\nM71\nG40 G1 X10\nM2\n"),
            (std::vector<std::string>{"SET_FEED_RATE(10.0000)", "COMMENT(\"interpreter: cutter radius compensation on left\")",
                                      "STRAIGHT_FEED(" + at(5, 0.5, 0) + ")",
                                      "COMMENT(\"interpreter: cutter radius compensation off\")",
                                      "STRAIGHT_FEED(" + at(10, 0, 0) + ")"}));
  struct Bad {
    const char* text;
    int line, column;
    const char* says;
  };
  for (const Bad& b : {Bad{"F1\nM70\nM71\nM72\nM2\n", 4, 1, "no modal state saved"},
                       Bad{"o1 sub\nM70\no1 endsub\no1 call\nM72\nM2\n", 5, 1, "no modal state saved"},
                       Bad{"M70\no1 sub\nM72\no1 endsub\no1 call\nM2\n", 3, 1, "no modal state saved"},
                       Bad{"M70\nF3\nM72 G0 X1\nM2\n", 3, 1, "line of its own"},
                       Bad{"F3 M70\nM2\n", 1, 4, "line of its own"},
                       Bad{"F3\nG41.1 D1\nM70\nM2\n", 3, 1, "compensation"}}) {
    const GcodeError e = error_of(b.text);
    EXPECT_EQ(e.line, b.line) << b.text;
    EXPECT_EQ(e.column, b.column) << b.text << e.message;
    EXPECT_NE(e.message.find(b.says), std::string::npos) << b.text << e.message;
  }
}

}  // namespace rs274_words_test
}  // namespace tnv::gcode
