// The LinuxCNC-dialect interpreter on its own (the rs274 comparison is
// tools/gcode/oracle, label gcode-oracle): calls, refusals, expressions,
// control flow, tool table and .var files.
#include "tools/gcode/canon_interpreter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace tnv::gcode {
namespace {

std::vector<std::string> calls_of(const std::string& text, const CanonSetup& setup = {}) {
  const CanonResult r = interpret_canon(text, setup);
  EXPECT_FALSE(r.error.has_value()) << (r.error ? to_string(*r.error) : "");
  std::vector<std::string> out;
  for (std::size_t k = 6; k < r.calls.size(); ++k) out.push_back(r.calls[k].text);  // after the start-up calls
  return out;
}

GcodeError error_of(const std::string& text, const CanonSetup& setup = {}) {
  const CanonResult r = interpret_canon(text, setup);
  EXPECT_TRUE(r.error.has_value()) << "accepted: " << text;
  EXPECT_TRUE(r.calls.empty()) << "a refused program returns no call";
  return r.error.value_or(GcodeError{});
}

const std::vector<std::string> kEnd = {"SET_G5X_OFFSET(1, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
                                       "SET_XY_ROTATION(0.0000)", "SET_FEED_MODE(0, 0)", "SET_FEED_RATE(0.0000)",
                                       "STOP_SPINDLE_TURNING(0)", "SET_SPINDLE_MODE(0 0.0000)", "PROGRAM_END()"};

std::vector<std::string> with_end(std::vector<std::string> v) {
  v.insert(v.end(), kEnd.begin(), kEnd.end());
  return v;
}

TEST(CanonInterpreter, StartUpCallsAsRs274PrintsThem) {
  const CanonResult r = interpret_canon("M2\n");
  ASSERT_FALSE(r.error);
  ASSERT_GE(r.calls.size(), 6u);
  EXPECT_EQ(r.calls[0].text, "USE_LENGTH_UNITS(CANON_UNITS_MM)");
  EXPECT_EQ(r.calls[5].text, "ON_RESET()");
  EXPECT_EQ(r.calls.back().text, "PROGRAM_END()");
  EXPECT_EQ(r.calls.back().line, 1);
}

TEST(CanonInterpreter, MovesArcsAndHelixInEachPlane) {
  EXPECT_EQ(calls_of("G0 X1 Y2 Z3\nG1 X4 F100\nG2 X5 Y3 I0.5 J0.5\nG3 X6 Y4 Z1 R2\nM2\n"),
            with_end({"STRAIGHT_TRAVERSE(1.0000, 2.0000, 3.0000, 0.0000, 0.0000, 0.0000)", "SET_FEED_RATE(100.0000)",
                      "STRAIGHT_FEED(4.0000, 2.0000, 3.0000, 0.0000, 0.0000, 0.0000)",
                      "ARC_FEED(5.0000, 3.0000, 4.5000, 2.5000, -1, 3.0000, 0.0000, 0.0000, 0.0000)",
                      "ARC_FEED(6.0000, 4.0000, 4.1771, 4.8229, 1, 1.0000, 0.0000, 0.0000, 0.0000)"}));
  // G18: first axis Z, second X, the helix along Y; a full circle of two turns.
  const auto xz = calls_of("F10\nG18 G2 X0 Z0 I1 K0 Y2 P2\nM2\n");
  ASSERT_GE(xz.size(), 3u);
  EXPECT_EQ(xz[2], "ARC_FEED(0.0000, 0.0000, 0.0000, 1.0000, -2, 2.0000, 0.0000, 0.0000, 0.0000)");
}

// The operator's block delete switch: on (LinuxCNC's default) skips a line
// that starts with '/', off runs it; a '/' elsewhere is no switch at all.
TEST(CanonInterpreter, BlockDeleteSwitchSkipsOrRunsTheSlashedLines) {
  const std::string program = "G0 X1\n/G0 X2\nG0 X3 (/ not at the start)\nM2\n";
  const std::string x2 = "STRAIGHT_TRAVERSE(2.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)";
  const std::vector<std::string> on = calls_of(program);
  EXPECT_EQ(std::count(on.begin(), on.end(), x2), 0) << "switch on: the slashed line ran";
  EXPECT_EQ(on.size(), 3 + kEnd.size());  // X1, the comment, X3
  CanonSetup off;
  off.block_delete = false;
  const std::vector<std::string> run = calls_of(program, off);
  EXPECT_EQ(std::count(run.begin(), run.end(), x2), 1) << "switch off: the slashed line did not run";
  EXPECT_EQ(run.size(), 4 + kEnd.size());
}

TEST(CanonInterpreter, InchesArePrintedInTheProgramsUnits) {
  const auto c = calls_of("G0 X25.4\nG20\nG0 Y1\nM2\n");
  EXPECT_EQ(c[2], "STRAIGHT_TRAVERSE(1.0000, 1.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
}

TEST(CanonInterpreter, ToolLengthOffsetsComeFromTheTable) {
  CanonSetup setup;
  std::string error;
  ASSERT_TRUE(setup.tools.load_text("T1 P1 Z12.5 D6 ;end mill\nT2 P2 Z-3\n", error)) << error;
  const auto c = calls_of("T1 M6\nG43\nG0 Z0\nG43 H2\nG49\nM2\n", setup);
  EXPECT_EQ(c[0], "SELECT_TOOL(1)");
  EXPECT_EQ(c[3], "CHANGE_TOOL(1)");
  EXPECT_EQ(c[4], "USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 12.5000, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)");
  EXPECT_EQ(c[6], "USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 -3.0000, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)");
  const GcodeError e = error_of("T7 M6\nM2\n", setup);
  EXPECT_EQ(e.line, 1);
  EXPECT_EQ(e.column, 1);
  EXPECT_NE(e.message.find("tool 7 not found"), std::string::npos) << e.message;
}

TEST(CanonInterpreter, WorkOffsetsFromTheVarFileAndG10) {
  CanonSetup setup;
  std::string error;
  ASSERT_TRUE(setup.parameters.load_var_text("5241 10\n5242 -5\n", error)) << error;  // G55 X10 Y-5
  const auto c = calls_of("G55\nG0 X0 Y0\nG10 L20 P0 X1\nG0 X0\nM2\n", setup);
  EXPECT_EQ(c[0], "SET_G5X_OFFSET(2, 10.0000, -5.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
  EXPECT_EQ(c[3], "STRAIGHT_TRAVERSE(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
  EXPECT_EQ(c[4], "SET_G5X_OFFSET(2, 9.0000, -5.0000, 0.0000, 0.0000, 0.0000, 0.0000)") << "X0 is now 1 mm on";
  // With G92 in force, L20 still makes here the given value.
  const auto g92 = calls_of("G0 X5\nG92 X1\nG0 X3\nG10 L20 P0 X0\nM2\n");
  EXPECT_EQ(g92[3], "SET_G5X_OFFSET(1, 3.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
  EXPECT_FALSE(setup.parameters.load_var_text("5221 ten\n", error));
  EXPECT_NE(error.find("line 1"), std::string::npos) << error;
}

TEST(CanonInterpreter, ExpressionsParametersAndFunctions) {
  const auto c = calls_of(
      "#1=2\n#<r>=[#1*3]\n#<_g>=[atan[1]/[1]]\nG0 X[#<r>+1] Y[sqrt[16]] Z[2**3 mod 5]\n"
      "G0 X[#<_g>] Y[fix[-1.5]] Z[round[2.5]]\nG0 X[1 lt 2] Y[3 eq 3.00001] Z[-[1+1]]\nM2\n");
  EXPECT_EQ(c[0], "STRAIGHT_TRAVERSE(7.0000, 4.0000, 3.0000, 0.0000, 0.0000, 0.0000)");
  EXPECT_EQ(c[1], "STRAIGHT_TRAVERSE(45.0000, -2.0000, 3.0000, 0.0000, 0.0000, 0.0000)");
  EXPECT_EQ(c[2], "STRAIGHT_TRAVERSE(1.0000, 1.0000, -2.0000, 0.0000, 0.0000, 0.0000)");
  // Settings take effect after the line is read.
  EXPECT_EQ(calls_of("#1=1\n#1=2 G0 X#1\nM2\n")[0],
            "STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
}

TEST(CanonInterpreter, OWordControlFlow) {
  const auto c = calls_of(
      "o<step> sub\nG91 G0 X#1\nG90\no<step> endsub\n"
      "#<n>=0\no1 while [#<n> lt 3]\no<step> call [2]\n#<n>=[#<n>+1]\no1 endwhile\n"
      "o2 if [#<n> eq 3]\nG0 Y1\no2 elseif [1]\nG0 Y2\no2 else\nG0 Y3\no2 endif\n"
      "o3 repeat [2]\nG91 G0 Z1\nG90\no3 endrepeat\n"
      "o4 do\no4 break\nG0 Z99\no4 while [1]\nM2\n");
  std::vector<std::string> moves;
  for (const auto& s : c)
    if (s.rfind("STRAIGHT_TRAVERSE", 0) == 0) moves.push_back(s.substr(18, 24));
  EXPECT_EQ(moves, (std::vector<std::string>{"2.0000, 0.0000, 0.0000, ", "4.0000, 0.0000, 0.0000, ",
                                             "6.0000, 0.0000, 0.0000, ", "6.0000, 1.0000, 0.0000, ",
                                             "6.0000, 1.0000, 1.0000, ", "6.0000, 1.0000, 2.0000, "}));
}

TEST(CanonInterpreter, RefusalsNameTheWordLineAndColumn) {
  GcodeError e = error_of("G21\nG0 X1 A5\nM2\n");
  EXPECT_EQ(e.line, 2);
  EXPECT_EQ(e.column, 7);
  EXPECT_NE(e.message.find("word A"), std::string::npos) << e.message;
  e = error_of("G19 G41 D1\nM2\n");  // cutter radius compensation only in G17 (and G18)
  EXPECT_EQ(e.column, 5);
  EXPECT_NE(e.message.find("G41"), std::string::npos) << e.message;
  e = error_of("F100 S100 M3\nG87 X1 Y1 Z-1 R1\nM2\n");  // back boring needs I, J and K
  EXPECT_EQ(e.line, 2);
  EXPECT_NE(e.message.find("G87 needs I"), std::string::npos) << e.message;
  e = error_of("F100\nG81 X1 ^30 Z-1 R1\nM2\n");  // polar and X on one line
  EXPECT_NE(e.message.find("polar"), std::string::npos) << e.message;
  e = error_of("F100\nG18 G81 X1 Z-1 R1\nM2\n");  // in G18 the bottom is a Y
  EXPECT_NE(e.message.find("needs Y"), std::string::npos) << e.message;
  e = error_of("G1 X1\nM2\n");
  EXPECT_NE(e.message.find("zero feed rate"), std::string::npos) << e.message;
  e = error_of("X1\nM2\n");
  EXPECT_NE(e.message.find("without a G-code"), std::string::npos) << e.message;
  e = error_of("G0 X[1/0]\nM2\n");
  EXPECT_NE(e.message.find("divide by zero"), std::string::npos) << e.message;
  e = error_of("G0 X#<nope>\nM2\n");
  EXPECT_NE(e.message.find("#<nope> not defined"), std::string::npos) << e.message;
  e = error_of("G0 X1 X2\nM2\n");
  EXPECT_EQ(e.column, 7);
  e = error_of("G0 G1 X1\nM2\n");
  EXPECT_NE(e.message.find("modal group"), std::string::npos) << e.message;
  e = error_of("G0 X1\n");
  EXPECT_NE(e.message.find("program end"), std::string::npos) << e.message;
  CanonSetup short_run;
  short_run.max_lines_run = 1000;
  e = error_of("o1 while [1]\no1 endwhile\nM2\n", short_run);
  EXPECT_NE(e.message.find("lines run"), std::string::npos) << "an endless loop is an error, not a hang";
  e = error_of("F10 G2 X10 Y0 I1 J0\nM2\n");
  EXPECT_NE(e.message.find("radius"), std::string::npos) << e.message;
}

TEST(CanonInterpreter, RigidTapAsRs274PrintsIt) {
  // The spindle drives Z down and back at K per turn; the tool ends where it
  // started (the next G0 X0 keeps Y1 Z5).
  const auto c = calls_of("G0 X1 Y1 Z5\nS200 M4\nG33.1 Z-5 K1.25\nG0 X0\nM2\n");
  ASSERT_GE(c.size(), 7u);
  EXPECT_EQ(c[3], "START_SPEED_FEED_SYNC(1.250000,0)");
  EXPECT_EQ(c[4], "RIGID_TAP(1.0000, 1.0000, -5.0000)");
  EXPECT_EQ(c[5], "STOP_SPEED_FEED_SYNCH()");
  EXPECT_EQ(c[6], "STRAIGHT_TRAVERSE(0.0000, 1.0000, 5.0000, 0.0000, 0.0000, 0.0000)");
  EXPECT_NE(error_of("G33.1 Z-5 K1\nM2\n").message.find("spindle not turning"), std::string::npos);
  EXPECT_NE(error_of("S100 M3\nG33.1 Z-5\nM2\n").message.find("needs K"), std::string::npos);
  EXPECT_EQ(error_of("S100 M3\nG33.1 Z-5 K1 F10\nM2\n").column, 14);  // the F
}

TEST(CanonInterpreter, DrillingCycleAsRs274RunsIt) {
  const auto c = calls_of("G0 X0 Y0 Z5\nF100\nG81 X1 Y2 Z-1 R1\nX3\nG80\nM2\n");
  const std::vector<std::string> expected = {
      "STRAIGHT_TRAVERSE(0.0000, 0.0000, 5.0000, 0.0000, 0.0000, 0.0000)", "SET_FEED_RATE(100.0000)",
      "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)",
      "STRAIGHT_TRAVERSE(1.0000, 2.0000, 5.0000, 0.0000, 0.0000, 0.0000)",
      "STRAIGHT_TRAVERSE(1.0000, 2.0000, 1.0000, 0.0000, 0.0000, 0.0000)",
      "STRAIGHT_FEED(1.0000, 2.0000, -1.0000, 0.0000, 0.0000, 0.0000)",
      "STRAIGHT_TRAVERSE(1.0000, 2.0000, 1.0000, 0.0000, 0.0000, 0.0000)",
      "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.000000)", "SET_NAIVECAM_TOLERANCE(0.0000)",
      "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)",
      "STRAIGHT_TRAVERSE(3.0000, 2.0000, 1.0000, 0.0000, 0.0000, 0.0000)",
      "STRAIGHT_FEED(3.0000, 2.0000, -1.0000, 0.0000, 0.0000, 0.0000)",
      "STRAIGHT_TRAVERSE(3.0000, 2.0000, 1.0000, 0.0000, 0.0000, 0.0000)",
      "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.000000)", "SET_NAIVECAM_TOLERANCE(0.0000)",
      "COMMENT(\"interpreter: motion mode set to none\")"};
  EXPECT_EQ(c, with_end(expected));
}

TEST(CanonInterpreter, PercentDelimitedProgramAndBlockDelete) {
  const auto c = calls_of("%\n/G0 X5\nG0 X1 (MSG, hello)\n%\nG0 X9\n");
  EXPECT_EQ(c, (std::vector<std::string>{"MESSAGE(\" hello\")",
                                         "STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
                                         "FINISH()"}));
}

TEST(CanonInterpreter, ToolTableRefusesBadLines) {
  ToolTable t;
  std::string error;
  EXPECT_FALSE(t.load_text("T1 P1 Z1\nP2 Z1\n", error));
  EXPECT_NE(error.find("line 2"), std::string::npos) << error;
  EXPECT_FALSE(t.load_text("T1 Zx\n", error));
  EXPECT_TRUE(t.load_text("T1 P1 Z1\n", error));
  EXPECT_FALSE(t.load_text("T1 P1 Z1\nT1 P2\n", error)) << "a tool twice";
  ASSERT_NE(t.find(1), nullptr) << "a refused load keeps the table";
}

}  // namespace
}  // namespace tnv::gcode
