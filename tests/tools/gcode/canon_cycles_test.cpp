// The tapping and boring cycles G84, G85, G86, G89 and the rule that a
// cycle's R, Z, P and Q carry over only while the same cycle goes on, in
// the LinuxCNC-dialect interpreter. Each expected call sequence is what
// LinuxCNC's rs274 prints for the same program; the oracle test
// (test_tapping_and_boring_cycles_agree) compares the two on random runs.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/tools/gcode/canon_test_support.hpp"
#include "tools/gcode/canon_interpreter.hpp"

namespace tnv::gcode {
namespace cycles_test {

CanonSetup no_tools() { return test::setup_with_tools(""); }

// The calls of the one cycle line "G98 <cycle> X1 Y2 R2 Z-3" from Z5, spindle
// `spindle` at S500: from the switch to exact path to the switch back.
std::vector<std::string> cycle_calls(const std::string& cycle, const std::string& spindle = "M3") {
  const std::vector<std::string> all = test::calls_between_start_and_end(
      "G21 G17 G90 F100 S500 " + spindle + "\nG0 X0 Y0 Z5\nG98 " + cycle + " X1 Y2 R2 Z-3\nM2\n", no_tools());
  std::vector<std::string> out;
  bool in = false;
  for (const std::string& c : all) {
    in = in || c == "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)";
    if (in) out.push_back(c);
  }
  return out;
}

std::string at(const char* z) { return std::string("(1.0000, 2.0000, ") + z + ", 0.0000, 0.0000, 0.0000)"; }

TEST(CannedCycles, G85FeedsInAndOutToRThenRisesToTheClearance) {
  EXPECT_EQ(cycle_calls("G85"),
            (std::vector<std::string>{"SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)", "STRAIGHT_TRAVERSE" + at("5.0000"),
                                      "STRAIGHT_TRAVERSE" + at("2.0000"), "STRAIGHT_FEED" + at("-3.0000"),
                                      "STRAIGHT_FEED" + at("2.0000"), "STRAIGHT_TRAVERSE" + at("5.0000"),
                                      "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.000000)",
                                      "SET_NAIVECAM_TOLERANCE(0.0000)"}));
}

TEST(CannedCycles, G86DwellsStopsTheSpindleRisesAndRestartsItInItsDirection) {
  const std::vector<std::string> cw = cycle_calls("G86 P0.7");
  const std::vector<std::string> expected{"SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)",
                                          "STRAIGHT_TRAVERSE" + at("5.0000"),
                                          "STRAIGHT_TRAVERSE" + at("2.0000"),
                                          "STRAIGHT_FEED" + at("-3.0000"),
                                          "DWELL(0.7000)",
                                          "STOP_SPINDLE_TURNING(0)",
                                          "STRAIGHT_TRAVERSE" + at("5.0000"),
                                          "START_SPINDLE_CLOCKWISE(0)",
                                          "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.000000)",
                                          "SET_NAIVECAM_TOLERANCE(0.0000)"};
  EXPECT_EQ(cw, expected);
  const std::vector<std::string> ccw = cycle_calls("G86 P0.7", "M4");
  ASSERT_EQ(ccw.size(), expected.size());
  EXPECT_EQ(ccw[7], "START_SPINDLE_COUNTERCLOCKWISE(0)");
}

TEST(CannedCycles, G89DwellsAndFeedsOutToTheClearance) {
  EXPECT_EQ(cycle_calls("G89 P0.5"),
            (std::vector<std::string>{"SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)", "STRAIGHT_TRAVERSE" + at("5.0000"),
                                      "STRAIGHT_TRAVERSE" + at("2.0000"), "STRAIGHT_FEED" + at("-3.0000"),
                                      "DWELL(0.5000)", "STRAIGHT_FEED" + at("5.0000"),
                                      "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.000000)",
                                      "SET_NAIVECAM_TOLERANCE(0.0000)"}));
}

TEST(CannedCycles, G84TapsInReversesDwellsTapsOutWithTheOverridesOff) {
  EXPECT_EQ(cycle_calls("G84 P0.3"),
            (std::vector<std::string>{"SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)", "STRAIGHT_TRAVERSE" + at("5.0000"),
                                      "STRAIGHT_TRAVERSE" + at("2.0000"), "DISABLE_FEED_OVERRIDE()",
                                      "DISABLE_SPEED_OVERRIDE(0)", "STRAIGHT_FEED" + at("-3.0000"),
                                      "STOP_SPINDLE_TURNING(0)", "START_SPINDLE_COUNTERCLOCKWISE(0)", "DWELL(0.3000)",
                                      "STRAIGHT_FEED" + at("5.0000"), "STOP_SPINDLE_TURNING(0)",
                                      "START_SPINDLE_CLOCKWISE(0)", "ENABLE_FEED_OVERRIDE()",
                                      "ENABLE_SPEED_OVERRIDE(0)", "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.000000)",
                                      "SET_NAIVECAM_TOLERANCE(0.0000)"}));
}

TEST(CannedCycles, TappingAndBoringRefuseASpindleThatCannotDoThem) {
  const auto refusal = [](const std::string& text) { return test::refusal_of(text, no_tools()); };
  GcodeError e = refusal("G21 F100 S500 M4\nG0 Z5\nG84 X1 R2 Z-3\nM2\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_NE(e.message.find("counterclockwise"), std::string::npos) << e.message;
  e = refusal("G21 F100 S500\nG0 Z5\nG84 X1 R2 Z-3\nM2\n");
  EXPECT_NE(e.message.find("spindle stopped"), std::string::npos) << e.message;
  e = refusal("G21 F100 S500 M5\nG0 Z5\nG86 X1 R2 Z-3 P1\nM2\n");
  EXPECT_NE(e.message.find("G86 with the spindle stopped"), std::string::npos) << e.message;
  e = refusal("G21 F100 S500 M3\nG0 Z5\nG89 X1 R2 Z-3\nM2\n");  // G89 needs its dwell
  EXPECT_NE(e.message.find("G89 needs P"), std::string::npos) << e.message;
  e = refusal("G21 F100 S500 M3\nG0 Z5\nG85 X1 R2 Z-3 P1\nM2\n");  // G85 has no dwell
  EXPECT_NE(e.message.find("word P"), std::string::npos) << e.message;
}

TEST(CannedCycles, WordsCarryOverOnlyWhileTheSameCycleGoesOn) {
  const auto refusal = [](const std::string& body) {
    return test::refusal_of("G21 F100 S500 M3\nG0 X0 Y0 Z5\n" + body + "\nM2\n", no_tools());
  };
  // Another cycle, or the same one after G80 or after another motion, names R, Z, P and Q again.
  EXPECT_NE(refusal("G81 R2 Z-3 X1\nG82 R2 Z-3 X2").message.find("G82 needs P"), std::string::npos);
  EXPECT_NE(refusal("G81 R2 Z-3 X1\nG82 R2 P1 X2").message.find("G82 needs Z"), std::string::npos);
  EXPECT_NE(refusal("G83 R2 Z-3 X1 Q1\nG73 R2 Z-3 X2").message.find("G73 needs Q"), std::string::npos);
  GcodeError e = refusal("G81 R2 Z-3 X1\nG80\nG81 X2");
  EXPECT_EQ(e.line, 5);
  EXPECT_NE(e.message.find("G81 needs R"), std::string::npos) << e.message;
  EXPECT_NE(refusal("G81 R2 Z-3 X1\nG0 X0\nG81 X2").message.find("G81 needs R"), std::string::npos);
  // While it goes on, a line of X alone drills again with R Z P of the first line.
  const std::vector<std::string> c = test::calls_between_start_and_end(
      "G21 F100 S500 M3\nG0 X0 Y0 Z5\nG82 R2 Z-3 X1 P0.4\nX2\nG82 Y1\nG80\nM2\n", no_tools());
  int dwells = 0;
  for (const std::string& s : c) dwells += s == "DWELL(0.4000)";
  EXPECT_EQ(dwells, 3);
}

}  // namespace cycles_test
}  // namespace tnv::gcode
