#include "tools/gcode/gcode_program.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "tests/tools/gcode/test_piece_path.hpp"

namespace tnv::gcode {
namespace {

using test::test_piece_path;

using fw::motion::SegmentKind;

GcodeProgram parse_ok(const char* text) {
  const GcodeResult r = parse_gcode(text);
  EXPECT_FALSE(r.error.has_value()) << (r.error ? to_string(*r.error) : "");
  return r.program;
}

GcodeError parse_error(const char* text) {
  const GcodeResult r = parse_gcode(text);
  EXPECT_TRUE(r.error.has_value()) << "accepted: " << text;
  EXPECT_TRUE(r.program.segments.empty()) << "an error must return no segment";
  return r.error.value_or(GcodeError{});
}

TEST(GcodeProgram, LinesArcsDwellAndModalStateBecomeSegments) {
  const GcodeProgram p = parse_ok(
      "%\n"
      "N10 G17 G21 G90 (setup)\n"
      "N20 G0 X10 Y0 ; rapid\n"
      "N30 G1 X20 F600\n"
      "N40 Y10\n"
      "N50 G91 X-5 Y5\n"
      "N60 G90 G3 X5 Y25 I-5 J5\n"
      "N70 G4 P0.5\n"
      "N80 G2 X15 Y25 R5\n"
      "N90 M2\n");
  ASSERT_EQ(p.segments.size(), 7u);
  EXPECT_TRUE(p.ended);
  EXPECT_EQ(p.segments[0].kind, SegmentKind::line);
  EXPECT_DOUBLE_EQ(p.segments[0].feed_mm_s, GcodeOptions{}.rapid_feed_mm_s);
  EXPECT_DOUBLE_EQ(p.segments[1].feed_mm_s, 10.0) << "F is per minute";
  EXPECT_EQ(p.segments[2].end_mm, (PlanePoint{20.0, 10.0})) << "G1 and F are modal";
  EXPECT_EQ(p.segments[3].end_mm, (PlanePoint{15.0, 15.0})) << "G91 is incremental";
  EXPECT_EQ(p.segments[4].kind, SegmentKind::arc_ccw);
  EXPECT_EQ(p.segments[4].centre_mm, (PlanePoint{10.0, 20.0})) << "I/J are offsets from the start";
  EXPECT_EQ(p.segments[5].kind, SegmentKind::dwell);
  EXPECT_DOUBLE_EQ(p.segments[5].dwell_s, 0.5);
  EXPECT_EQ(p.segments[6].kind, SegmentKind::arc_cw);
  EXPECT_NEAR(p.segments[6].centre_mm[0], 10.0, 1e-12) << "R form, clockwise under 180 degrees";
  EXPECT_NEAR(p.segments[6].centre_mm[1], 25.0, 1e-12);
  EXPECT_EQ(p.segments[6].tag, 9u) << "tag = source line";
  EXPECT_NEAR(p.geometry[6].length_mm, std::numbers::pi * 5.0, 1e-9);
}

TEST(GcodeProgram, InchesScaleLengthsAndFeed) {
  // F is read before G20 on its own line (LinuxCNC's order), so G20 goes first.
  const GcodeProgram p = parse_ok("G20\nG1 X1 F60\nG21 X50.8\n");
  ASSERT_EQ(p.segments.size(), 2u);
  EXPECT_DOUBLE_EQ(p.segments[0].end_mm[0], 25.4);
  EXPECT_DOUBLE_EQ(p.segments[0].feed_mm_s, 25.4);
  EXPECT_DOUBLE_EQ(p.segments[1].end_mm[0], 50.8);
  EXPECT_DOUBLE_EQ(p.segments[1].feed_mm_s, 25.4) << "the feed stays what it was set to";
}

TEST(GcodeProgram, NegativeRPicksTheArcOverHalfACircle) {
  const GcodeProgram p = parse_ok("G1 X10 F600\nG3 X0 Y10 R-10\n");
  ASSERT_EQ(p.segments.size(), 2u);
  EXPECT_NEAR(p.geometry[1].length_mm, 1.5 * std::numbers::pi * 10.0, 1e-9);
}

TEST(GcodeProgram, InverseTimeMovesRunAtTheirLengthOverTheirTime) {
  // G93: 20 mm in 1/3 minute, then a half circle of radius 10 in 1/2
  // minute; the rapid is unaffected, and G94 with F goes back to per minute.
  const GcodeProgram p = parse_ok("G93\nG1 X20 F3\nG2 X40 Y0 I10 J0 F2\nG0 X0\nG94 F600\nG1 X5\n");
  ASSERT_EQ(p.segments.size(), 4u);
  EXPECT_NEAR(p.segments[0].feed_mm_s, 1.0, 1e-9);
  EXPECT_NEAR(p.segments[1].feed_mm_s, 10.0 * std::numbers::pi / 30.0, 1e-9);
  EXPECT_DOUBLE_EQ(p.segments[2].feed_mm_s, GcodeOptions{}.rapid_feed_mm_s);
  EXPECT_DOUBLE_EQ(p.segments[3].feed_mm_s, 10.0);
  EXPECT_NEAR(p.programmed_time_s(), 20.0 + 30.0 + 40.0 / GcodeOptions{}.rapid_feed_mm_s + 0.5, 1e-6);
}

TEST(GcodeProgram, ErrorsNameLineAndColumnAndUnsupportedWordsByName) {
  GcodeError e = parse_error("G95\n");
  EXPECT_EQ(e.column, 1);
  EXPECT_NE(e.message.find("G95"), std::string::npos) << e.message;

  e = parse_error("G1 X1 F100\n  M62 P1\n");
  EXPECT_EQ(e.line, 2);
  EXPECT_EQ(e.column, 3);
  EXPECT_NE(e.message.find("M62"), std::string::npos) << e.message;

  e = parse_error("G1 X1 F100 (open comment\n");
  EXPECT_NE(e.message.find("comment"), std::string::npos);
  EXPECT_EQ(e.column, 12);

  e = parse_error("X10\n");
  EXPECT_NE(e.message.find("without a G-code that uses them"), std::string::npos) << e.message;
  e = parse_error("G1 X10\n");
  EXPECT_NE(e.message.find("feed"), std::string::npos);
  e = parse_error("G1 X1 X2 F10\n");
  EXPECT_NE(e.message.find("twice"), std::string::npos);
  e = parse_error("G1 X F10\n");
  EXPECT_EQ(e.column, 6) << e.message;
  e = parse_error("G1 X10 F60\nG2 X21 Y0 I5 J1\n");  // end radius differs from start radius
  EXPECT_EQ(e.line, 2);
  EXPECT_NE(e.message.find("radius to the end of the arc differs"), std::string::npos) << e.message;
  e = parse_error("G1 X300 F60\n");
  EXPECT_NE(e.message.find("outside_workspace"), std::string::npos) << e.message;
  e = parse_error("G1 X10 F60\nG3 X40 Y0 R5\n");
  EXPECT_NE(e.message.find("R too small"), std::string::npos) << e.message;
}

// As in LinuxCNC, nothing after M2 is read.
TEST(GcodeProgram, LinesAfterTheProgramEndAreNotRun) {
  const GcodeProgram p = parse_ok("G1 X10 F60\nM2\nG1 X20\n");
  EXPECT_TRUE(p.ended);
  ASSERT_EQ(p.segments.size(), 1u);
  EXPECT_EQ(p.lines_run, 2u);
}

TEST(GcodeProgram, TheRepositoryTestPiecesParse) {
  for (const char* name : {"nas979_diamond_circle_square.ngc", "corners_90deg.ngc", "circle_chords_0p1mm.ngc",
                           "spiral.ngc"}) {
    const GcodeResult r = parse_gcode_file(test_piece_path(name));
    ASSERT_FALSE(r.error.has_value()) << name << ": " << to_string(*r.error);
    EXPECT_TRUE(r.program.ended) << name;
    EXPECT_GT(r.program.segments.size(), 3u) << name;
  }
}

// A FIFO is refused at once (never waited on), and so is a directory.
TEST(GcodeProgram, AProgramFileMustBeARegularFile) {
  const std::string dir = (std::filesystem::temp_directory_path() / ("tnv_gcode_" + std::to_string(::getpid()))).string();
  std::filesystem::create_directories(dir);
  const std::string fifo = dir + "/program.ngc";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string text;
  std::string error;
  EXPECT_FALSE(read_program_file(fifo, text, error));
  EXPECT_NE(error.find("not a regular file"), std::string::npos) << error;
  EXPECT_FALSE(read_program_file(dir, text, error));
  EXPECT_NE(error.find("a directory, not a regular file"), std::string::npos) << error;
  const GcodeResult r = parse_gcode_file(fifo);
  ASSERT_TRUE(r.error.has_value());
  EXPECT_TRUE(r.program.segments.empty());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tnv::gcode
