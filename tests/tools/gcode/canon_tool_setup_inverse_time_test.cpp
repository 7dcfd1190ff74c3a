// G10 L1 / L10 / L11 (a program edits its tool table) and G93 (inverse-time
// feed) in the LinuxCNC-dialect interpreter. Each expected call is what
// LinuxCNC's rs274 prints for the same program (its offsets in inches, this
// machine's in millimetres); the oracle test compares
// programs/tool_table_edits_inverse_time.ngc with it call by call. Each
// refusal names its line and column and returns no call.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include "tests/tools/gcode/canon_test_support.hpp"
#include "tools/gcode/canon_interpreter.hpp"

namespace tnv::gcode {
namespace tool_setup_inverse_time_test {

// The third tool line is the table's pocket 3 whatever its T and P.
CanonSetup tools_setup() { return test::setup_with_tools("T1 P1 Z2.5 D1.25\nT2 P7 Z5 D2.5\nT9 P4 Z10 D6 Q3\n"); }

std::vector<std::string> calls_of(const std::string& text) { return test::calls_between_start_and_end(text, tools_setup()); }

GcodeError error_of(const std::string& text) { return test::refusal_of(text, tools_setup()); }

std::string entry(int pocket, int tool, const std::string& xyz, const std::string& rest) {
  return "SET_TOOL_TABLE_ENTRY(" + std::to_string(pocket) + ", " + std::to_string(tool) + ", " + xyz +
         " 0.0000 0.0000 0.0000 0.0000 0.0000 0.0000, " + rest + ")";
}

std::string offset_z(const std::string& z) {
  return "USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 " + z + ", 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)";
}

TEST(CanonToolSetup, L1SetsTheEntryAndTheSpindlesWhenTheToolIsInItAndG43ReadsTheNewLength) {
  const auto c = calls_of("T2 M6\nG43\nG10 L1 P2 Z7.5 R1\nG43\nG10 L1 P9 X0.5 Z4 I12 J34 Q2\nG43 H9\nM2\n");
  const std::vector<std::string> expected = {
      "SELECT_TOOL(2)", "START_CHANGE()", "STOP_SPINDLE_TURNING(0)", "CHANGE_TOOL(2)", offset_z("5.0000"),
      // The length changes for the next G43, not at once (rs274 makes no offset call here).
      entry(2, 2, "0.0000 0.0000 7.5000", "0.0000, 0.0000, 0"), entry(0, 2, "0.0000 0.0000 7.5000", "0.0000, 0.0000, 0"),
      offset_z("7.5000"),
      // Tool 9 is not in the spindle: its own entry only; Y, D and the rest kept.
      entry(3, 9, "0.5000 0.0000 4.0000", "12.0000, 34.0000, 2"),
      "USE_TOOL_LENGTH_OFFSET(0.5000 0.0000 4.0000, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)"};
  EXPECT_EQ(c, expected);
}

TEST(CanonToolSetup, L1InInchesStoresMillimetresAndRSetsTheDiameterCompensationUses) {
  const auto c = calls_of("G20\nG10 L1 P1 Z1 R0.05\nG21\nG0 X-10 Y0\nG41 D1\nG1 X0 F100\nG40\nG0 X-10\nM2\n");
  ASSERT_GE(c.size(), 2u);
  EXPECT_EQ(c[1], entry(1, 1, "0.0000 0.0000 25.4000", "0.0000, 0.0000, 0"));
  // D1 is now 2.54 mm across: the entry move ends 1.27 mm to the left of X0 Y0.
  bool found = false;
  for (const std::string& call : c)
    found = found || call == "STRAIGHT_FEED(0.0000, 1.2700, 0.0000, 0.0000, 0.0000, 0.0000)";
  EXPECT_TRUE(found);
}

TEST(CanonToolSetup, L10AndL11MeasureFromTheToolPointWithoutItsLengthOffset) {
  // Machine Z 16 + 5 (tool 2's length) = 21 in G54; L10 Z18 makes the
  // length 3, so that G43 reads Z18 here. G92 (enabled) is taken off.
  auto c = calls_of("T2 M6\nG43\nG0 Z16\nG92 Z10\nG10 L10 P2 Z18\nM2\n");
  EXPECT_NE(std::find(c.begin(), c.end(), entry(2, 2, "0.0000 0.0000 -3.0000", "0.0000, 0.0000, 0")), c.end());
  // L11 measures in G59.3 (its Z -6) and keeps G92: the tool point at
  // machine Z 21 is Z 27 there; Z2.5 makes the length 24.5.
  c = calls_of("T2 M6\nG43\nG0 Z16\nG10 L2 P9 Z-6\nG92 Z1\nG10 L11 P2 Z2.5 X1\nM2\n");
  EXPECT_NE(std::find(c.begin(), c.end(), entry(2, 2, "-1.0000 0.0000 24.5000", "0.0000, 0.0000, 0")), c.end());
}

// G92.2 keeps the G92 offsets but takes them off, and #5210 (G92 applied)
// says so: 0 after G92.2, 1 after G92.3, so L10 measures without G92 and
// then with it again. rs274 prints the same (Z 0.1181 and -0.1181 inches;
// random seed 9418 found it).
TEST(CanonToolSetup, L10AfterG92_2MeasuresWithoutTheG92Offset) {
  const auto c =
      calls_of("T2 M6\nG43\nG0 Z16\nG92 Z10\nG92.2\n(DEBUG,#5210)\nG10 L10 P2 Z18\nG92.3\n(DEBUG,#5210)\n"
               "G10 L10 P2 Z18\nM2\n");
  const auto at = [&c](const std::string& call) { return std::find(c.begin(), c.end(), call) - c.begin(); };
  const auto off = at("MESSAGE(\"0.000000\")"), on = at("MESSAGE(\"1.000000\")");
  const auto without = at(entry(2, 2, "0.0000 0.0000 3.0000", "0.0000, 0.0000, 0"));
  const auto with = at(entry(2, 2, "0.0000 0.0000 -3.0000", "0.0000, 0.0000, 0"));
  const auto end = static_cast<std::ptrdiff_t>(c.size());
  ASSERT_LT(off, end);
  ASSERT_LT(on, end);
  ASSERT_LT(without, end);
  ASSERT_LT(with, end);
  EXPECT_LT(off, without);
  EXPECT_LT(without, on);
  EXPECT_LT(on, with);
}

TEST(CanonToolSetup, BadPAndQAreRefusedAsRs274RefusesThem) {
  GcodeError e = error_of("G10 L1 Z1\nM2\n");
  EXPECT_EQ(e.line, 1);
  EXPECT_NE(e.message.find("tool number"), std::string::npos) << e.message;
  e = error_of("G0 X1\nG10 L1 P2.4 Z1\nM2\n");
  EXPECT_EQ(e.line, 2);
  EXPECT_EQ(e.column, 8);  // the P word
  EXPECT_NE(e.message.find("whole tool number"), std::string::npos) << e.message;
  e = error_of("G10 L10 P0 Z1\nM2\n");
  EXPECT_EQ(e.column, 9);
  e = error_of("G10 L1 P3 Z1\nM2\n");  // no tool 3 (P2.6 rounds to it as well, as in rs274)
  EXPECT_NE(e.message.find("tool 3 not found"), std::string::npos) << e.message;
  EXPECT_NE(error_of("G10 L1 P2.6 Z1\nM2\n").message.find("tool 3 not found"), std::string::npos);
  EXPECT_NE(error_of("G10 L1 P2\nM2\n").message.find("changes nothing"), std::string::npos);
  e = error_of("G10 L1 P2 Q10\nM2\n");
  EXPECT_EQ(e.column, 11);
  EXPECT_NE(error_of("G10 L1 P2 Q2.5\nM2\n").message.find("whole number"), std::string::npos);
  EXPECT_NE(error_of("G10 L1 P2 Q-2\nM2\n").message.find("whole number"), std::string::npos);
  EXPECT_NE(error_of("G10 L2 P1 X1 I3\nM2\n").message.find("G10 L2"), std::string::npos);
  // P2.5 is tool 3 for rs274 too; R may be negative and Q-1 is "no Q".
  EXPECT_EQ(calls_of("G10 L1 P1.5 Q-1 R-1\nM2\n")[0], entry(2, 2, "0.0000 0.0000 5.0000", "0.0000, 0.0000, 0"));
}

TEST(CanonToolSetup, AnEditChangesNothingBeforeItsLineAndTheSetupsTableStaysAsLoaded) {
  const CanonSetup setup = tools_setup();
  const CanonResult r = interpret_canon("G43 H1\nG10 L1 P1 Z9\nG43 H1\nM2\n", setup);
  ASSERT_FALSE(r.error);
  EXPECT_EQ(setup.tools.find(1)->offset[2], 2.5);
  // A second run starts again from the table as loaded.
  const CanonResult again = interpret_canon("G43 H1\nM2\n", setup);
  ASSERT_FALSE(again.error);
  EXPECT_EQ(again.calls[6].text, offset_z("2.5000"));
}

TEST(CanonInverseTime, EachFeedMoveGetsItsLengthTimesFAsItsRateAndG94GoesBack) {
  const auto c = calls_of("G93\nG1 X10 F2\nG0 X0 Y0\nG2 X10 Y0 I5 J0 Z3 P2 F2\nG1 X10 F4\nG94 F300\nG1 X0\nM2\n");
  const std::vector<std::string> expected = {
      "COMMENT(\"interpreter: feed mode set to inverse time\")", "SET_FEED_MODE(0, 0)", "SET_FEED_RATE(20.0000)",
      "STRAIGHT_FEED(10.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
      "STRAIGHT_TRAVERSE(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
      // One turn and a half of radius 5 rising 3: hypot(15 pi, 3) x 2.
      "SET_FEED_RATE(94.4386)", "ARC_FEED(10.0000, 0.0000, 5.0000, 0.0000, -2, 3.0000, 0.0000, 0.0000, 0.0000)",
      // No motion: rs274's lower bound of 0.1.
      "SET_FEED_RATE(0.1000)", "STRAIGHT_FEED(10.0000, 0.0000, 3.0000, 0.0000, 0.0000, 0.0000)",
      "COMMENT(\"interpreter: feed mode set to units per minute\")", "SET_FEED_MODE(0, 0)", "SET_FEED_RATE(0.0000)",
      "SET_FEED_RATE(300.0000)", "STRAIGHT_FEED(0.0000, 0.0000, 3.0000, 0.0000, 0.0000, 0.0000)"};
  EXPECT_EQ(c, expected);
}

TEST(CanonInverseTime, TheMachineGetsThePathFeedOfEachMove) {
  // A 10 mm move in 1/2 minute runs at 20 mm/min; in inches the rate is
  // converted as any feed rate is (0.606 inch, from X10 mm to X1 inch, in
  // 1/3 minute: 46.2 mm/min).
  const CanonResult r = interpret_canon("G93\nG1 X10 F2\nG20\nG1 X1 F3\nM2\n", tools_setup());
  ASSERT_FALSE(r.error);
  std::vector<double> rates;
  for (const CanonCall& call : r.calls)
    if (call.motion.kind == CanonMotion::Kind::feed_rate) rates.push_back(call.motion.value);
  ASSERT_GE(rates.size(), 2u);
  EXPECT_DOUBLE_EQ(rates[0], 20.0);
  EXPECT_NEAR(rates[1], 3.0 * (25.4 - 10.0) / 25.4 * 25.4, 1e-9);
}

TEST(CanonInverseTime, AMoveWithoutItsOwnFIsRefusedAndFAloneSetsNoRate) {
  GcodeError e = error_of("G93 F10\nG1 X10\nM2\n");
  EXPECT_EQ(e.line, 2);
  EXPECT_NE(e.message.find("needs its own F"), std::string::npos) << e.message;
  e = error_of("G93\nG1 X1 F2\nG2 X3 I1\nM2\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_NE(e.message.find("needs its own F"), std::string::npos) << e.message;
  // F in G93 is the move's, not a rate: rs274 prints no SET_FEED_RATE for it.
  EXPECT_EQ(calls_of("G93 F10\nM2\n").size(), 2u);
  // Canned cycles and probes have no rate in G93 (rs274: zero feed rate).
  EXPECT_NE(error_of("G93\nG81 X1 Y1 Z-1 R1 F2\nM2\n").message.find("G93"), std::string::npos);
  EXPECT_NE(error_of("G93\nG38.2 Z-1 F2\nM2\n").message.find("G93"), std::string::npos);
  EXPECT_EQ(error_of("G93 G94\nM2\n").column, 5);
}

TEST(CanonInverseTime, M2EndsItAndThePredefinedParametersSayIt) {
  const auto c = calls_of("G93\n(debug,#<_inverse_time> #<_units_per_minute>)\nG1 X3 F2\n(debug,#<_feed>)\nM2\n");
  ASSERT_GE(c.size(), 6u);
  EXPECT_EQ(c[2], "MESSAGE(\"1.000000 0.000000\")");
  EXPECT_EQ(c[5], "MESSAGE(\"6.000000\")");
  const CanonResult r = interpret_canon("G93\nM2\n", tools_setup());
  ASSERT_FALSE(r.error);
  EXPECT_EQ(r.calls.back().text, "PROGRAM_END()");
}

}  // namespace tool_setup_inverse_time_test
}  // namespace tnv::gcode
