// The interpreter's calls in structured form and their conversion to this
// XY table's segments (canon_segments.hpp).
#include "tools/gcode/canon_segments.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "tools/gcode/gcode_program.hpp"

namespace tnv::gcode {
namespace {

using fw::motion::Segment;
using fw::motion::SegmentKind;
using Kind = CanonMotion::Kind;

// G54 at X10 Y5 (machine coordinates), tool 1 of length 25 mm.
GcodeOptions offsets_and_tools() {
  GcodeOptions o;
  std::string error;
  EXPECT_TRUE(o.canon.parameters.load_var_text("5221 10\n5222 5\n", error)) << error;
  EXPECT_TRUE(o.canon.tools.load_text("T1 P1 Z25 D6\n", error)) << error;
  return o;
}

const CanonCall& first_of(const CanonResult& r, Kind kind) {
  for (const CanonCall& c : r.calls)
    if (c.motion.kind == kind) return c;
  ADD_FAILURE() << "no call of that kind";
  return r.calls.front();
}

TEST(CanonMotion, MovesAreInMachineMillimetresWhileTheTextStaysInProgramUnits) {
  CanonSetup setup = offsets_and_tools().canon;
  const CanonResult r = interpret_canon("G20\nG0 X1 Y2\nF10\nG2 X2 Y1 I1 J0\nG4 P1.5\nT1 M6\nM2\n", setup);
  ASSERT_FALSE(r.error) << to_string(*r.error);
  const CanonCall& rapid = first_of(r, Kind::traverse);
  EXPECT_EQ(rapid.text, "STRAIGHT_TRAVERSE(1.0000, 2.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
  EXPECT_EQ(rapid.line, 2);
  EXPECT_NEAR(rapid.motion.end_mm[0], 10.0 + 25.4, 1e-9);
  EXPECT_NEAR(rapid.motion.end_mm[1], 5.0 + 50.8, 1e-9);
  EXPECT_NEAR(first_of(r, Kind::feed_rate).motion.value, 254.0, 1e-9) << "F10 in G20: inches per minute";
  const CanonMotion& arc = first_of(r, Kind::arc).motion;
  EXPECT_EQ(arc.plane, 17);
  EXPECT_EQ(arc.turn, -1) << "G2: clockwise";
  EXPECT_NEAR(arc.centre_mm[0], 10.0 + 50.8, 1e-9);
  EXPECT_NEAR(arc.centre_mm[1], 5.0 + 50.8, 1e-9);
  EXPECT_NEAR(arc.end_mm[0], 10.0 + 50.8, 1e-9);
  EXPECT_NEAR(arc.end_mm[1], 5.0 + 25.4, 1e-9);
  EXPECT_DOUBLE_EQ(first_of(r, Kind::dwell).motion.value, 1.5) << "seconds, whatever the units";
  EXPECT_DOUBLE_EQ(first_of(r, Kind::tool_change).motion.value, 1.0);
  EXPECT_EQ(r.calls.back().motion.kind, Kind::end);
}

// G43 shifts program Z by the tool's length: a move without Z stays at the
// machine Z it is at, a move to Z0 goes to the tool's length above it.
TEST(CanonMotion, TheToolLengthOffsetIsInMachineZ) {
  const CanonResult r = interpret_canon("T1 M6\nG43\nG0 X0\nG0 Z0\nM2\n", offsets_and_tools().canon);
  ASSERT_FALSE(r.error) << to_string(*r.error);
  const CanonCall& rapid = first_of(r, Kind::traverse);
  EXPECT_EQ(rapid.text, "STRAIGHT_TRAVERSE(0.0000, -5.0000, -25.0000, 0.0000, 0.0000, 0.0000)");
  EXPECT_NEAR(rapid.motion.end_mm[0], 10.0, 1e-9);
  EXPECT_NEAR(rapid.motion.end_mm[1], 0.0, 1e-9);
  EXPECT_NEAR(rapid.motion.end_mm[2], 0.0, 1e-9) << "machine Z stays";
  const CanonCall& down = r.calls[static_cast<std::size_t>(&rapid - r.calls.data()) + 1];
  EXPECT_EQ(down.text, "STRAIGHT_TRAVERSE(0.0000, -5.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
  EXPECT_NEAR(down.motion.end_mm[2], 25.0, 1e-9) << "program Z0 is the tool's length from machine Z0";
}

TEST(CanonSegments, ADialectProgramWithOffsetsASubroutineAnArcAndADwell) {
  GcodeOptions o = offsets_and_tools();
  o.start_mm = {10.0, 5.0};
  const GcodeResult r = parse_gcode(
      "o<square> sub\n"                // 1
      "  G91 G1 X#1 F600\n"             // 2
      "  Y#1\n"                         // 3
      "  G90\n"                         // 4
      "o<square> endsub\n"              // 5
      "T1 M6 M3 M8\n"                   // 6
      "G0 X0 Y0\n"                      // 7
      "o<square> call [4]\n"            // 8
      "G2 X8 Y0 I0 J-4\n"               // 9: from (4, 4) about (4, 0), a quarter circle
      "G4 P0.5\n"                       // 10
      "G10 L2 P1 X20\n"                 // 11
      "G0 X0\n"                         // 12
      "M30\n",
      o);
  ASSERT_FALSE(r.error) << to_string(*r.error);
  const GcodeProgram& p = r.program;
  ASSERT_EQ(p.segments.size(), 7u);
  EXPECT_EQ(p.segments[0].spindle, fw::motion::SpindleChange::stop) << "M6 stops the spindle (rs274's STOP_SPINDLE_TURNING)";
  EXPECT_TRUE(p.segments[1].pause) << "M6 is a manual tool change: the program pauses";
  EXPECT_EQ(p.segments[1].tag, 6u);
  ASSERT_EQ(p.pauses.size(), 1u);
  EXPECT_EQ(p.pauses[0].segment, 1u);
  EXPECT_EQ(p.pauses[0].reason, PauseReason::tool_change);
  EXPECT_EQ(p.pauses[0].tool, 1);
  EXPECT_EQ(p.segments[2].end_mm, (PlanePoint{14.0, 5.0})) << "G0 X0 Y0 was the table's start: no segment";
  EXPECT_EQ(p.segments[2].tag, 2u) << "the subroutine's line";
  EXPECT_DOUBLE_EQ(p.segments[2].feed_mm_s, 10.0);
  EXPECT_EQ(p.segments[3].end_mm, (PlanePoint{14.0, 9.0}));
  EXPECT_EQ(p.segments[4].kind, SegmentKind::arc_cw);
  EXPECT_EQ(p.segments[4].centre_mm, (PlanePoint{14.0, 5.0}));
  EXPECT_EQ(p.segments[4].end_mm, (PlanePoint{18.0, 5.0}));
  EXPECT_EQ(p.segments[4].tag, 9u);
  EXPECT_EQ(p.segments[5].kind, SegmentKind::dwell);
  EXPECT_DOUBLE_EQ(p.segments[5].dwell_s, 0.5);
  EXPECT_EQ(p.segments[6].end_mm, (PlanePoint{20.0, 5.0})) << "G10 L2 moved G54's X to 20";
  EXPECT_DOUBLE_EQ(p.segments[6].feed_mm_s, o.rapid_feed_mm_s);
  EXPECT_TRUE(p.ended);
  EXPECT_EQ(p.tool_changes, 1u);
  EXPECT_EQ(p.spindle_starts, 1u);
  EXPECT_EQ(p.coolant_starts, 1u);
  // The definition is read once where it stands (and skipped), its other four lines run at the call.
  EXPECT_EQ(p.lines_run, 13u);
  const double arc_mm = 2.0 * std::numbers::pi;
  EXPECT_NEAR(p.programmed_length_mm(), 4.0 + 4.0 + arc_mm + 2.0, 1e-9);
  EXPECT_NEAR(p.programmed_time_s(), (8.0 + arc_mm) / 10.0 + 0.5 + 2.0 / o.rapid_feed_mm_s, 1e-9);
}

TEST(CanonSegments, AZMoveIsALineInXyzAndAPlungeALineInZ) {
  const GcodeResult r = parse_gcode("G0 X1\nG1 X2 Z-1 F100\nG1 Z-3\nG0 Z0\nM2\n");
  ASSERT_FALSE(r.error) << to_string(*r.error);
  ASSERT_EQ(r.program.segments.size(), 4u);
  EXPECT_EQ(r.program.segments[1].end_mm, (PlanePoint{2.0, 0.0, -1.0}));
  EXPECT_EQ(r.program.segments[2].end_mm, (PlanePoint{2.0, 0.0, -3.0}));
  EXPECT_TRUE(r.program.segments[3].rapid);
  EXPECT_EQ(r.program.segments[3].end_mm, (PlanePoint{2.0, 0.0, 0.0}));
  EXPECT_NEAR(r.program.programmed_length_mm(), 1.0 + std::hypot(1.0, 1.0) + 2.0 + 3.0, 1e-12);
}

TEST(CanonSegments, AG17HelixSharesItsZAmongItsTurnsByAngle) {
  // From (10, 0, 0) about the origin: a full turn, then a quarter, 5 mm down in all.
  const GcodeResult r = parse_gcode("G1 X10 F600\nG3 X0 Y10 Z-5 I-10 P2\nM2\n");
  ASSERT_FALSE(r.error) << to_string(*r.error);
  ASSERT_EQ(r.program.segments.size(), 3u);
  EXPECT_NEAR(r.program.segments[1].end_mm[2], -4.0, 1e-12) << "2 pi of 2.5 pi";
  EXPECT_EQ(r.program.segments[2].end_mm, (PlanePoint{0.0, 10.0, -5.0}));
  const double turn_mm = std::hypot(2.0 * std::numbers::pi * 10.0, 4.0);
  EXPECT_NEAR(r.program.geometry[1].length_mm, turn_mm, 1e-9);
  EXPECT_NEAR(r.program.geometry[2].length_mm, turn_mm / 4.0, 1e-9) << "the same pitch throughout";
}

TEST(CanonSegments, AToolsLengthMovesMachineZFromItsNextZWord) {
  const GcodeOptions o = offsets_and_tools();
  const GcodeResult ok = parse_gcode("T1 M6\nG43\nG0 X1\nM2\n", o);
  ASSERT_FALSE(ok.error) << to_string(*ok.error);
  EXPECT_EQ(ok.program.tool_changes, 1u);
  EXPECT_EQ(ok.program.segments.back().end_mm[2], 0.0) << "no Z word: Z stays";
  const GcodeResult r = parse_gcode("T1 M6\nG43\nG0 X1 Z0\nM2\n", o);
  ASSERT_FALSE(r.error) << to_string(*r.error);
  EXPECT_EQ(r.program.segments.back().end_mm[2], 25.0) << "program Z0 with the 25 mm tool is machine Z 25";
}

TEST(CanonSegments, ARefusalInASubroutineFileNamesTheFile) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("tnv_canon_segments_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "plunge.ngc") << "(a subroutine file)\no<plunge> sub\n  G1 X300 F100\no<plunge> endsub\nM2\n";
  std::ofstream(dir / "main.ngc") << "G0 X1\no<plunge> call\nM2\n";
  const GcodeResult r = parse_gcode_file((dir / "main.ngc").string());
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(r.error);
  EXPECT_EQ(r.error->line, 3) << "the line in the file";
  EXPECT_NE(r.error->file.find("plunge.ngc"), std::string::npos) << to_string(*r.error);
}

TEST(CanonSegments, ArcsInG18AndG19BecomeArcsInTheirPlanes) {
  using fw::motion::ArcPlane;
  // G18: clockwise from Z towards X is the other way; the centre's Z and X from K and I, Y where it starts.
  GcodeResult r = parse_gcode("G1 X5 F60\nG18 G2 X10 I2.5 K0 Y-1\nM2\n");
  ASSERT_FALSE(r.error) << to_string(*r.error);
  ASSERT_EQ(r.program.segments.size(), 2u);
  const fw::motion::Segment& zx = r.program.segments[1];
  EXPECT_EQ(zx.plane, ArcPlane::zx);
  EXPECT_EQ(zx.kind, fw::motion::SegmentKind::arc_cw);
  EXPECT_EQ(zx.centre_mm, (PlanePoint{7.5, 0.0, 0.0}));
  EXPECT_EQ(zx.end_mm, (PlanePoint{10.0, -1.0, 0.0}));
  EXPECT_NEAR(r.program.geometry[1].sweep_rad, -std::numbers::pi, 1e-12);
  EXPECT_NEAR(r.program.geometry[1].point_at(0.5 * r.program.geometry[1].length_mm)[2], -2.5, 1e-9)
      << "clockwise in G18 from X = 5 to X = 10 passes below";
  // G19 with P2: two full turns in YZ, X shared by angle; the R form too.
  r = parse_gcode("G19 G3 Y0 Z0 J2 K0 X4 P2 F60\nG2 Y4 Z0 R2\nM2\n");
  ASSERT_FALSE(r.error) << to_string(*r.error);
  ASSERT_EQ(r.program.segments.size(), 3u);
  for (const fw::motion::Segment& s : r.program.segments) EXPECT_EQ(s.plane, ArcPlane::yz);
  EXPECT_NEAR(r.program.segments[0].end_mm[0], 2.0, 1e-12) << "half of X after the first turn";
  EXPECT_EQ(r.program.segments[1].end_mm, (PlanePoint{4.0, 0.0, 0.0}));
  EXPECT_NEAR(r.program.segments[2].centre_mm[1], 2.0, 1e-9);
  EXPECT_NEAR(r.program.programmed_length_mm(), 2.0 * std::hypot(4.0 * std::numbers::pi, 2.0) + 2.0 * std::numbers::pi,
              1e-9);
  // An arc whose top leaves the travel is refused with its line, nothing to send.
  fw::motion::MotionLimits limits;
  limits.axis[2].position_max_mm = 2.0;
  GcodeOptions o;
  o.limits = limits;
  r = parse_gcode("G1 X5 F60\nG18 G3 X10 I2.5 K0\nM2\n", o);
  ASSERT_TRUE(r.error);
  EXPECT_EQ(r.error->line, 2);
  EXPECT_NE(r.error->message.find("outside_workspace"), std::string::npos) << r.error->message;
  EXPECT_TRUE(r.program.segments.empty());
}

TEST(CanonSegments, ArcTurnsPBecomeFullCirclesThenTheArc) {
  const GcodeResult r = parse_gcode("G1 X10 F600\nG3 X0 Y10 I-10 P3\nM2\n");
  ASSERT_FALSE(r.error) << to_string(*r.error);
  ASSERT_EQ(r.program.segments.size(), 4u);
  EXPECT_NEAR(r.program.programmed_length_mm(), 10.0 + (2.0 + 0.25) * 2.0 * std::numbers::pi * 10.0, 1e-6);
}

TEST(CanonSegments, WhatTheTableCannotDoIsRefusedWithItsLine) {
  for (const auto& [text, line, what] : {std::tuple{"F60\nG38.2 X5\nM2\n", 2, "probe"},
                                         std::tuple{"F60\nG5.1 X5 I1 J1\nM2\n", 2, "spline"},
                                         std::tuple{"G1 X300 F60\nM2\n", 1, "outside_workspace"}}) {
    const GcodeResult r = parse_gcode(text);
    ASSERT_TRUE(r.error) << text;
    EXPECT_EQ(r.error->line, line) << text;
    EXPECT_NE(r.error->message.find(what), std::string::npos) << r.error->message;
    EXPECT_TRUE(r.program.segments.empty());
  }
}

TEST(CanonSegments, M0AndM6PauseAndM1PausesOnlyWithTheOptionalStopSwitchOn) {
  const char* text = "G1 X1 F60\nM0\nG1 X2\nM1\nT3 M6\nG1 X3\nM2\n";
  GcodeOptions with_tool;
  std::string error;
  ASSERT_TRUE(with_tool.canon.tools.load_text("T3 P3 Z0\n", error)) << error;
  const GcodeResult on = parse_gcode(text, with_tool);
  ASSERT_FALSE(on.error) << to_string(*on.error);
  ASSERT_EQ(on.program.segments.size(), 7u) << "three lines, three pauses and M6's spindle stop";
  ASSERT_EQ(on.program.pauses.size(), 3u);
  const PauseReason reasons[] = {PauseReason::program_stop, PauseReason::optional_stop, PauseReason::tool_change};
  const std::uint32_t lines[] = {2, 4, 5};
  for (std::size_t k = 0; k < 3; ++k) {
    const ProgramPause& pause = on.program.pauses[k];
    EXPECT_EQ(pause.reason, reasons[k]);
    const Segment& s = on.program.segments.at(pause.segment);
    EXPECT_TRUE(s.pause);
    EXPECT_EQ(s.kind, SegmentKind::dwell);
    EXPECT_EQ(s.tag, lines[k]);
  }
  EXPECT_EQ(on.program.pauses[2].tool, 3);
  EXPECT_EQ(on.program.optional_stops_skipped, 0u);

  GcodeOptions off = with_tool;
  off.canon.optional_stop = false;
  const GcodeResult r = parse_gcode(text, off);
  ASSERT_FALSE(r.error) << to_string(*r.error);
  ASSERT_EQ(r.program.pauses.size(), 2u) << "M1 runs through with the switch off";
  EXPECT_EQ(r.program.pauses[0].reason, PauseReason::program_stop);
  EXPECT_EQ(r.program.pauses[1].reason, PauseReason::tool_change);
  EXPECT_EQ(r.program.segments.size(), 6u);
  EXPECT_EQ(r.program.optional_stops_skipped, 1u);
  EXPECT_NE(summary_text(r.program).find("1 optional stop skipped"), std::string::npos) << summary_text(r.program);
}

// M60 (a pallet change) makes rs274's calls, PALLET_SHUTTLE() then
// PROGRAM_STOP(), after the line's move; this machine has no shuttle, so a
// machine run pauses there as at M0 (the operator changes the part),
// whatever the optional stop switch says.
TEST(CanonSegments, M60IsAPalletShuttleAndAProgramStopAndPausesTheRun) {
  const CanonResult c = interpret_canon("G21 G90\nG1 X1 F100\nM60 G1 X3\nG1 X2\nM2\n");
  ASSERT_FALSE(c.error) << to_string(*c.error);
  std::vector<std::string> after_feed;
  bool seen = false;
  for (const CanonCall& call : c.calls) {
    if (call.text.rfind("STRAIGHT_FEED(3.0000", 0) == 0) seen = true;
    else if (seen && after_feed.size() < 3) after_feed.push_back(call.text);
  }
  EXPECT_EQ(after_feed, (std::vector<std::string>{"PALLET_SHUTTLE()", "PROGRAM_STOP()",
                                                   "STRAIGHT_FEED(2.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)"}));
  for (const bool optional_stop : {true, false}) {
    GcodeOptions o;
    o.canon.optional_stop = optional_stop;
    const GcodeResult r = parse_gcode("G21 G90\nG1 X1 F100\nM60 G1 X3\nG1 X2\nM2\n", o);
    ASSERT_FALSE(r.error) << to_string(*r.error);
    ASSERT_EQ(r.program.pauses.size(), 1u);
    EXPECT_EQ(r.program.pauses[0].reason, PauseReason::pallet_change);
    EXPECT_EQ(to_string(r.program.pauses[0]), "pallet change (M60)");
    const Segment& pause = r.program.segments.at(r.program.pauses[0].segment);
    EXPECT_TRUE(pause.pause);
    EXPECT_EQ(pause.tag, 3u);
    EXPECT_EQ(r.program.pauses[0].segment, 2u) << "after the line's own move";
  }
}

// S, M3, M4 and M5 become spindle elements in program order: a new S while
// it turns is a new speed, M3 at S0 is a stop until an S, a command that
// changes nothing is not sent, and the program's end stops only a spindle
// the program started.
TEST(CanonSegments, SpindleCommandsAreSentInProgramOrder) {
  using fw::motion::SpindleChange;
  const GcodeResult r = parse_gcode(
      "M3\n"             // 1: at S0: a stop
      "S1000\n"          // 2: now it turns
      "G1 X1 F60\n"      // 3
      "S1000\n"          // 4: no change: not sent
      "S2000 M4\n"       // 5: S first, then M4: forward 2000, then reverse 2000
      "G1 X2\n"          // 6
      "M5\n"             // 7
      "G1 X3\n"          // 8
      "M2\n");           // 9: stopped already: no stop at the end
  ASSERT_FALSE(r.error) << to_string(*r.error);
  struct Expected {
    std::uint32_t line;
    SpindleChange change;
    double rpm;
  };
  const Expected expected[] = {{1, SpindleChange::stop, 0.0},     {2, SpindleChange::forward, 1000.0},
                               {5, SpindleChange::forward, 2000.0}, {5, SpindleChange::reverse, 2000.0},
                               {7, SpindleChange::stop, 0.0}};
  std::vector<const Segment*> changes;
  for (const Segment& s : r.program.segments)
    if (s.spindle != SpindleChange::none) changes.push_back(&s);
  ASSERT_EQ(changes.size(), std::size(expected));
  for (std::size_t k = 0; k < changes.size(); ++k) {
    EXPECT_EQ(changes[k]->tag, expected[k].line) << k;
    EXPECT_EQ(changes[k]->spindle, expected[k].change) << k;
    EXPECT_EQ(changes[k]->spindle_rpm, expected[k].rpm) << k;
    EXPECT_EQ(changes[k]->kind, SegmentKind::dwell);
  }
  EXPECT_EQ(r.program.spindle_changes, 5u);
  EXPECT_EQ(r.program.segments.size(), 8u) << "three moves and five spindle commands";
  EXPECT_NE(summary_text(r.program).find("5 spindle commands"), std::string::npos) << summary_text(r.program);

  const GcodeResult left_on = parse_gcode("S500 M3\nG1 X1 F60\nM30\n");
  ASSERT_FALSE(left_on.error);
  ASSERT_EQ(left_on.program.segments.size(), 3u);
  EXPECT_EQ(left_on.program.segments.back().spindle, SpindleChange::stop) << "M30 stops the spindle it started";
  EXPECT_EQ(left_on.program.segments.back().tag, 3u);
  const GcodeResult none = parse_gcode("G1 X1 F60\nM2\n");
  ASSERT_FALSE(none.error);
  EXPECT_EQ(none.program.segments.size(), 1u) << "a program without spindle commands gets none";
}

TEST(CanonSegments, AProgramMayEndAtTheEndOfItsFileWhileTheCanonTextStillRefusesThat) {
  const GcodeResult r = parse_gcode("G1 X10 F600\n");
  ASSERT_FALSE(r.error) << to_string(*r.error);
  EXPECT_EQ(r.program.segments.size(), 1u);
  EXPECT_FALSE(r.program.ended);
  EXPECT_TRUE(interpret_canon("G1 X10 F600\n").error) << "rs274 refuses it, and so does the text compared with it";
}

TEST(CanonSegments, TheInterpretersErrorIsTheResultsWithItsColumn) {
  const GcodeResult r = parse_gcode("G1 X1 F100\nG1 X2 Q5\nM2\n");
  ASSERT_TRUE(r.error);
  EXPECT_EQ(r.error->line, 2);
  EXPECT_EQ(r.error->column, 7);
}

}  // namespace
}  // namespace tnv::gcode
