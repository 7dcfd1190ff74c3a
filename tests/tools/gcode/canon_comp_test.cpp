// Cutter radius compensation (G40/G41/G42/G41.1/G42.1) in the LinuxCNC-dialect
// interpreter. Each expected call is what LinuxCNC's rs274 prints for the
// same program (tools/gcode/oracle compares the two on the samples and
// programs/cam_contour_g41_g42.ngc); the comments give the geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "tests/tools/gcode/canon_test_support.hpp"
#include "tools/gcode/canon_interpreter.hpp"

namespace tnv::gcode {
namespace cutter_comp_test {

// Diameters in millimetres: T2 2.5, T3 3.75, T4 5, T8 10.
CanonSetup tools_setup() { return test::setup_with_tools("T2 P2 D2.5\nT3 P3 D3.75\nT4 P4 D5\nT8 P8 D10\n"); }

std::vector<std::string> moves_of(const std::string& text) {
  return test::calls_between_start_and_end(text, tools_setup());
}

GcodeError error_of(const std::string& text) { return test::refusal_of(text, tools_setup()); }

std::string feed(const std::string& xyz) { return "STRAIGHT_FEED(" + xyz + ", 0.0000, 0.0000, 0.0000)"; }

// Tool radius 2.5 (T4) on the left of X0Y0 -> X10Y0 -> X10Y10 -> X0Y10 -> X0Y20.
TEST(CutterCompensation, EntryConcaveCornerConvexArcAndExit) {
  const auto c = moves_of("F100\nG0 X0 Y0\nG41 D4\nG1 X10 Y0\nG1 X10 Y10\nG1 X0 Y10\nG1 X0 Y20\nG40\nG1 X-5 Y25\nM2\n");
  const std::vector<std::string> expected = {
      "SET_FEED_RATE(100.0000)",
      "STRAIGHT_TRAVERSE(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
      "COMMENT(\"interpreter: cutter radius compensation on left\")",
      // Entry: 2.5 to the left of the programmed end, pulled back 2.5 (r / tan 45 deg)
      // to meet the offset of the next side: the concave corner's intersection.
      feed("7.5000, 2.5000, 0.0000"),
      feed("7.5000, 7.5000, 0.0000"),  // the second concave corner, the same way
      feed("0.0000, 7.5000, 0.0000"),  // to the convex corner at X0Y10 ...
      // ... rounded clockwise by an arc of the tool radius about the programmed corner.
      "ARC_FEED(-2.5000, 10.0000, 0.0000, 10.0000, -1, 0.0000, 0.0000, 0.0000, 0.0000)",
      feed("-2.5000, 20.0000, 0.0000"),  // G40 ends the last move where the tool is
      "COMMENT(\"interpreter: cutter radius compensation off\")",
      feed("-5.0000, 25.0000, 0.0000")};  // exit: straight to the programmed point
  EXPECT_EQ(c, expected);
}

TEST(CutterCompensation, RightSideEntryArcAroundACircleAndIntoAConcaveLine) {
  // Tool radius 2.5 on the right; a full circle of radius 10 about X10Y0 from
  // X0Y0, then a line inside it: arc to line meets where the offsets cross.
  const auto c = moves_of("F100\nG0 X0 Y-20\nG42 D4\nG1 X0 Y0\nG2 X0 Y0 I10 J0\nG1 X-1 Y1\nG40 G1 X-10 Y0\nM2\n");
  ASSERT_GE(c.size(), 8u);
  EXPECT_EQ(c[3], feed("2.5000, 0.0000, 0.0000"));  // right of the +Y entry: +X
  // Right of a clockwise path is inside the circle: radius 10 - 2.5 about X10Y0.
  EXPECT_EQ(c[4], "ARC_FEED(2.5000, 0.0000, 10.0000, 0.0000, -1, 0.0000, 0.0000, 0.0000, 0.0000)");
  // A convex corner at X0Y0 between the circle's end and the line to X-1Y1.
  EXPECT_EQ(c[5], "ARC_FEED(1.7678, 1.7678, 0.0000, 0.0000, 1, 0.0000, 0.0000, 0.0000, 0.0000)");
  EXPECT_EQ(c[6], feed("0.7678, 2.7678, 0.0000"));  // 2.5 right of X-1Y1 along the 135 deg line
}

TEST(CutterCompensation, EntryArcKeepsTheToolTangentToTheProgrammedCircle) {
  // G42 with T3 (radius 1.875) inside a clockwise arc from X30Y20 to X30Y30
  // about X30Y25: the end moves 1.875 towards the centre, and the tool's arc
  // is centred on that radius, equally far from the start and the new end.
  const auto c = moves_of("F100\nG0 X30 Y20\nG42 D3\nG2 X30 Y30 I0 J5\nG40 G1 X30 Y20\nM2\n");
  ASSERT_GE(c.size(), 4u);
  EXPECT_EQ(c[3], "ARC_FEED(30.0000, 28.1250, 30.0000, 24.0625, -1, 0.0000, 0.0000, 0.0000, 0.0000)");
}

// An ill-conditioned entry arc (from the random program of seed 3546): G41
// with a 0.625 mm tool radius on a counterclockwise arc of radius 10.94 mm
// turns into an arc of radius 415 mm over a 2.6 mm chord. Its centre moves
// 1.4e-4 mm for 5.4e-9 mm of tool radius, so it is checked against rs274's
// numbers for the same diameter to the last bit (1.25 mm; docs/gcode.md), and
// by its geometry: equally far from the start and the new end, and the new
// end one tool radius from the programmed end towards the programmed centre.
TEST(CutterCompensation, AFlatEntryArcHasLinuxCncsCentreAndIsAnArc) {
  const CanonResult r = interpret_canon(
      "G21 G17 G90 F840\nG0 X-39.0761 Y-16.4317\nG41 D1\nG91 G3 X-2.2001 Y2.9142 I-9.7088 J-5.0422\nG90\nG40\nM2\n",
      test::setup_with_tools("T1 P1 D1.25\n"));
  ASSERT_FALSE(r.error.has_value()) << to_string(*r.error);
  const auto arc = std::find_if(r.calls.begin(), r.calls.end(),
                                [](const CanonCall& c) { return c.motion.kind == CanonMotion::Kind::arc; });
  ASSERT_NE(arc, r.calls.end());
  // rs274 -g with the tool table T1 D0.04921259842519685 (inches): the same call.
  EXPECT_EQ(arc->text, "ARC_FEED(-41.7052, -13.9720, 243.0659, 287.7782, 1, 0.0000, 0.0000, 0.0000, 0.0000)");
  const double sx = -39.0761, sy = -16.4317;
  const auto& c = arc->motion.centre_mm;
  const auto& e = arc->motion.end_mm;
  const double radius = std::hypot(c[0] - e[0], c[1] - e[1]);
  EXPECT_NEAR(radius, 414.907, 1e-3);
  EXPECT_NEAR(std::hypot(c[0] - sx, c[1] - sy), radius, 1e-9);
  const double px = sx - 2.2001, py = sy + 2.9142;          // the programmed end
  const double ox = sx - 9.7088, oy = sy - 5.0422;          // the programmed centre
  const double inward = std::atan2(oy - py, ox - px);       // left of a counterclockwise arc: inside
  EXPECT_NEAR(e[0], px + 0.625 * std::cos(inward), 1e-12);
  EXPECT_NEAR(e[1], py + 0.625 * std::sin(inward), 1e-12);
}

TEST(CutterCompensation, DiameterFromTheToolTableOrTheSpindleOrG41_1) {
  // D2: diameter 2.5, the entry ends 1.25 left of X10Y0.
  EXPECT_EQ(moves_of("F1\nG41 D2\nG1 X10\nG40\nG1 X0\nM2\n")[2], feed("10.0000, 1.2500, 0.0000"));
  // No D: the tool in the spindle (T3, diameter 3.75).
  auto c = moves_of("F1\nT3 M6\nG41\nG1 X10\nG40\nG1 X0\nM2\n");
  EXPECT_EQ(c[6], feed("10.0000, 1.8750, 0.0000"));
  // G41.1 D6: a diameter in program units, no table.
  EXPECT_EQ(moves_of("F1\nG41.1 D6\nG1 X10\nG40\nG1 X0\nM2\n")[2], feed("10.0000, 3.0000, 0.0000"));
  // In inches: G41.1 D0.2 is 0.1 inch to the side.
  c = moves_of("G20 F1\nG41.1 D0.2\nG1 X1\nG40\nG1 X0\nM2\n");
  EXPECT_EQ(c[3], feed("1.0000, 0.1000, 0.0000"));
  // A negative diameter compensates on the other side.
  EXPECT_EQ(moves_of("F1\nG42.1 D-6\nG1 X10\nG40\nG1 X0\nM2\n")[1],
            "COMMENT(\"interpreter: cutter radius compensation on left\")");
}

TEST(CutterCompensation, CallsMadeMeanwhileWaitBehindTheQueuedMove) {
  // F200 and a comment come after the move they follow is known, as in rs274;
  // a message or a tool selection is made at once.
  const auto c = moves_of("F100\nG41 D4\nG1 X10\nG1 X10 Y10 F200\n(a comment)\n(MSG,now)\nT2\nG1 X0 Y10\nG40\nG1 X0 Y0\nM2\n");
  const std::vector<std::string> expected = {
      "SET_FEED_RATE(100.0000)", "COMMENT(\"interpreter: cutter radius compensation on left\")",
      feed("7.5000, 2.5000, 0.0000"), "SET_FEED_RATE(200.0000)", "MESSAGE(\"now\")", "SELECT_TOOL(2)",
      feed("7.5000, 7.5000, 0.0000"), "COMMENT(\"a comment\")", feed("0.0000, 7.5000, 0.0000"),
      "COMMENT(\"interpreter: cutter radius compensation off\")", feed("0.0000, 0.0000, 0.0000")};
  EXPECT_EQ(c, expected);
}

TEST(CutterCompensation, GougingCornersAndArcsTooSmallAreRefused) {
  // A slot 2 wide for a tool 10 wide: the pulled-back move would run backwards.
  GcodeError e = error_of("F100\nG41 D8\nG1 X10 Y0\nG1 X10 Y2\nG1 X0 Y2\nG40 G1 X0 Y-10\nM2\n");
  EXPECT_EQ(e.line, 5);
  EXPECT_EQ(e.column, 1);
  EXPECT_NE(e.message.find("gouging"), std::string::npos) << e.message;
  // An inside arc of radius 4 for a tool of radius 5.
  e = error_of("F100\nG41 D8\nG1 X10 Y0\nG3 X10 Y8 R4\nG40 G1 X0 Y0\nM2\n");
  EXPECT_EQ(e.line, 4);
  EXPECT_NE(e.message.find("arc's radius"), std::string::npos) << e.message;
  // An entry no longer than the tool radius (a Z-only first move).
  e = error_of("F100\nG41 D4\nG1 Z-1\nM2\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_NE(e.message.find("entry move"), std::string::npos) << e.message;
}

TEST(CutterCompensation, WhatLinuxCncRefusesWhileCompensating) {
  const std::string on = "F100\nG41 D4\nG1 X10\n";
  for (const char* line : {"G92 X0", "M6 T2", "G43 H2", "G49", "G55", "G28", "G53 G1 X0", "G81 X5 Y5 Z-1 R1",
                           "G18", "G64 P0.1", "G61", "G98", "G10 L2 P1 X1", "G10 L20 P0 X1", "G41 D2"}) {
    const GcodeError e = error_of(on + line + "\nG40\nM2\n");
    EXPECT_EQ(e.line, 4) << line;
    EXPECT_GE(e.column, 1) << line;
  }
  // The move after G40 must be straight.
  const GcodeError e = error_of(on + "G40 G2 X20 Y0 I5\nM2\n");
  EXPECT_NE(e.message.find("straight"), std::string::npos) << e.message;
  // D is a tool number for G41/G42 and needs them; G41.1 needs D; only G17/G18.
  EXPECT_NE(error_of("G41 D2.5\nM2\n").message.find("whole number"), std::string::npos);
  EXPECT_NE(error_of("G41 D99\nM2\n").message.find("not found"), std::string::npos);
  EXPECT_NE(error_of("G41.1\nM2\n").message.find("needs D"), std::string::npos);
  EXPECT_NE(error_of("G0 X1 D2\nM2\n").message.find("word D"), std::string::npos);
  EXPECT_EQ(error_of("G19 G41 D2\nM2\n").column, 5);
}

TEST(CutterCompensation, IncrementalMovesCountFromTheProgrammedPoint) {
  // G91 X5 after X10Y10 goes to the programmed X15Y10, not the tool's X12.5.
  const auto c = moves_of("F100\nG41 D4\nG1 X10\nG1 Y10\nG91 G1 X5\nG90 G40 G1 X20 Y20\nM2\n");
  ASSERT_GE(c.size(), 6u);
  EXPECT_EQ(c[3], feed("7.5000, 10.0000, 0.0000"));
  EXPECT_EQ(c[5], "ARC_FEED(10.0000, 12.5000, 10.0000, 10.0000, -1, 0.0000, 0.0000, 0.0000, 0.0000)");
  EXPECT_EQ(c[6], feed("15.0000, 12.5000, 0.0000"));
}

TEST(CutterCompensation, AProgramEndingAtPercentStillMakesTheWaitingMove) {
  // rs274 drops the last queued move here (docs/gcode.md, deviations): this
  // interpreter ends it where the tool is, as G40 or M2 would.
  const CanonResult r = interpret_canon("%\nF100\nG41 D4\nG1 X10\nG1 X10 Y10\n%\n", tools_setup());
  ASSERT_FALSE(r.error.has_value());
  ASSERT_GE(r.calls.size(), 3u);
  EXPECT_EQ(r.calls[r.calls.size() - 3].text, feed("7.5000, 2.5000, 0.0000"));
  EXPECT_EQ(r.calls[r.calls.size() - 2].text, feed("7.5000, 10.0000, 0.0000"));
  EXPECT_EQ(r.calls.back().text, "FINISH()");
}

}  // namespace cutter_comp_test
}  // namespace tnv::gcode
