// LinuxCNC's predefined read-only parameters (#<_x>, #<_motion_mode>, ...,
// #5400-#5413, #5420-#5428) in the LinuxCNC-dialect interpreter. Each
// expected value is what LinuxCNC's rs274 prints for the same (DEBUG,...)
// line; the oracle test (test_predefined_parameters_agree) compares the two
// on random programs.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/tools/gcode/canon_test_support.hpp"
#include "tools/gcode/canon_interpreter.hpp"

namespace tnv::gcode {
namespace predefined_test {

CanonSetup tools_setup() { return test::setup_with_tools("T2 P2 Z12.7 D6.35\nT3 P3 X5.08 Z2.54 D2.54 I10 J20 Q3\n"); }

std::vector<std::string> messages_of(const std::string& text) {
  std::vector<std::string> out;
  for (const std::string& c : test::calls_between_start_and_end(text, tools_setup()))
    if (c.rfind("MESSAGE(", 0) == 0) out.push_back(c);
  return out;
}

TEST(PredefinedParameters, TheModesReadAsLinuxCncNumbersThem) {
  const auto m = messages_of(
      "G20 G90 F10 S1000 M4 M8\nG10 L2 P2 X1 Y2 Z3\nG55\nT2 M6\nG43\nT3\nG18\nG1 X1.5 Y2 Z-1\nG91.1\nG98\n"
      "(DEBUG,#<_x> #<_y> #<_z> #<_motion_mode> #<_plane> #<_metric> #<_imperial> #<_absolute>)\n"
      "(DEBUG,#<_coord_system> #<_feed> #<_rpm> #<_current_tool> #<_selected_tool> #<_spindle_on> #<_flood>)\n"
      "(DEBUG,#<_tool_offset> #<_retract_old_z> #<_ijk_absolute_mode> #<_units_per_minute> #<_line>)\nM2\n");
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[0], "MESSAGE(\"1.500000 2.000000 -1.000000 10.000000 180.000000 0.000000 1.000000 1.000000\")");
  // M6 stops the spindle, as in LinuxCNC: _spindle_on is 0 after M4 then T2 M6.
  EXPECT_EQ(m[1], "MESSAGE(\"550.000000 10.000000 1000.000000 2.000000 3.000000 0.000000 1.000000\")");
  EXPECT_EQ(m[2], "MESSAGE(\"1.000000 1.000000 0.000000 1.000000 13.000000\")");
}

TEST(PredefinedParameters, PositionToolAndCallLevelAreTheStateWhenTheBlockIsRead) {
  const auto m = messages_of(
      "o100 sub\n(DEBUG,#<_call_level> #<_line>)\no100 return [7]\no100 endsub\nG21 F100 T3 M6 M3 S500\n"
      "o100 call\n(DEBUG,#<_value> #<_value_returned> #<_call_level> #<_spindle_on> #<_spindle_cw>)\n"
      "G1 X10 Y4\n#1 = [#5420 + #<_line> + #5421]\n(DEBUG,#1 #5400 #5401 #5403 #5410 #5411 #5412 #5413 #5422)\nM2\n");
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[0], "MESSAGE(\"1.000000 2.000000\")");
  EXPECT_EQ(m[1], "MESSAGE(\"7.000000 1.000000 0.000000 1.000000 1.000000\")");
  // #1 = 10 + 9 (its line) + 4; the tool table's T3 as the table holds it.
  EXPECT_EQ(m[2], "MESSAGE(\"23.000000 3.000000 5.080000 2.540000 2.540000 10.000000 20.000000 3.000000 0.000000\")");
}

TEST(PredefinedParameters, AssigningOneIsRefusedWithItsNameLineAndColumn) {
  GcodeError e = test::refusal_of("G21\nG1 X1 F1\n  #<_x> = 5\nM2\n", tools_setup());
  EXPECT_EQ(e.line, 3);
  EXPECT_EQ(e.column, 3);
  EXPECT_NE(e.message.find("read-only parameter #<_x>"), std::string::npos) << e.message;
  e = test::refusal_of("G21\n#<_value> = 1\nM2\n", tools_setup());
  EXPECT_NE(e.message.find("read-only parameter #<_value>"), std::string::npos) << e.message;
  e = test::refusal_of("G21\n#5421 = 1\nM2\n", tools_setup());
  EXPECT_EQ(e.line, 2);
  EXPECT_NE(e.message.find("#5421 is read-only"), std::string::npos) << e.message;
  // The numbers around the read-only ranges stay writable.
  EXPECT_EQ(messages_of("G21\n#5399 = 1\n#5414 = 2\n#5419 = 3\n#5429 = 4\n(DEBUG,#5399 #5414 #5419 #5429)\nM2\n"),
            std::vector<std::string>{"MESSAGE(\"1.000000 2.000000 3.000000 4.000000\")"});
}

TEST(PredefinedParameters, AnUnsetGlobalPrintsHashesAndIsAnErrorInAnExpression) {
  EXPECT_EQ(messages_of("G21\n#<_mine> = 3\n(DEBUG,#<_mine> #<_never_set> #<_x>)\nM2\n"),
            std::vector<std::string>{"MESSAGE(\"3.000000 ###### 0.000000\")"});
  const GcodeError e = test::refusal_of("G21\n#1 = [#<_never_set> + 1]\nM2\n", tools_setup());
  EXPECT_EQ(e.line, 2);
  EXPECT_NE(e.message.find("#<_never_set> not defined"), std::string::npos) << e.message;
  // A name LinuxCNC predefines but this interpreter leaves undefined (docs/gcode.md).
  EXPECT_NE(test::refusal_of("G21\n#1 = #<_current_pocket>\nM2\n", tools_setup()).message.find("not defined"),
            std::string::npos);
}

}  // namespace predefined_test
}  // namespace tnv::gcode
