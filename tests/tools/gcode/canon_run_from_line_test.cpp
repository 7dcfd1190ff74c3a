// Run from line N (docs/gcode.md "Run from line"): the modal state made
// again, the approach (Z up, XY, down), the lines before N evaluated but
// silent, the refusals, and the oracle: LinuxCNC's rs274 has no run from
// line, so the calls from N on must equal the tail of a full run.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <optional>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "tests/sanitized_build.hpp"
#include "tests/tools/gcode/canon_test_support.hpp"
#include "tools/gcode/canon_interpreter.hpp"

// A namespace of its own: the unity build joins this file with the other
// G-code tests, whose helpers have the same names.
namespace tnv::gcode::run_from_line_test {
namespace {

constexpr std::size_t kStartUpCalls = 6;  // USE_LENGTH_UNITS .. ON_RESET

CanonSetup with_tools() {
  std::string text;
  for (int t = 1; t <= 20; ++t)  // as the oracle's table: length 2.5 t, diameter 1.25 t
    text += "T" + std::to_string(t) + " P" + std::to_string(t) + " Z" + std::to_string(2.5 * t) + " D" +
            std::to_string(1.25 * t) + "\n";
  return test::setup_with_tools(text);
}

CanonSetup from(int line, CanonSetup setup = with_tools()) {
  setup.from_line = RunFromLine{};
  setup.from_line->line = line;
  return setup;
}

std::vector<std::string> texts(const std::vector<CanonCall>& calls, std::size_t first = kStartUpCalls) {
  std::vector<std::string> out;
  for (std::size_t k = first; k < calls.size(); ++k) out.push_back(calls[k].text);
  return out;
}

std::vector<std::string> run(const std::string& program, const CanonSetup& setup) {
  const CanonResult r = interpret_canon(program, setup);
  EXPECT_FALSE(r.error) << (r.error ? to_string(*r.error) : "");
  return texts(r.calls);
}

GcodeError refusal(const std::string& program, const CanonSetup& setup) { return test::refusal_of(program, setup); }

std::string traverse(double x, double y, double z) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "STRAIGHT_TRAVERSE(%.4f, %.4f, %.4f, 0.0000, 0.0000, 0.0000)", x, y, z);
  return buf;
}

std::string feed(double x, double y, double z) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "STRAIGHT_FEED(%.4f, %.4f, %.4f, 0.0000, 0.0000, 0.0000)", x, y, z);
  return buf;
}

const std::vector<std::string> kEnd = {"SET_G5X_OFFSET(1, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
                                       "SET_XY_ROTATION(0.0000)",  "SET_FEED_MODE(0, 0)",
                                       "SET_FEED_RATE(0.0000)",    "STOP_SPINDLE_TURNING(0)",
                                       "SET_SPINDLE_MODE(0 0.0000)"};

TEST(CanonRunFromLine, RebuildsUnitsPlaneOffsetToolSpindleCoolantAndFeed) {
  const std::string program =
      "G21 G18 G90\n"                // 1
      "G10 L2 P3 X10 Y20 Z-100\n"    // 2
      "G56\n"                        // 3: G54..G59.3 index 3
      "T2 M6\n"                      // 4
      "G43\n"                        // 5: tool 2, 5 mm
      "S1200 M4\n"                   // 6
      "M7\nM8\n"                     // 7, 8
      "F250 G64 P0.05\n"             // 9
      "G0 X1 Y2 Z3\n"                // 10
      "G1 X5\n"                      // 11
      "M2\n";
  // The machine at machine 0 0 0 is program (-10, -20, 100 - 5); the
  // clearance (machine Z 0) is program Z 95.
  const std::vector<std::string> expected = {
      "COMMENT(\"interpreter: run from line 11\")",
      "USE_LENGTH_UNITS(CANON_UNITS_MM)",
      "SET_G5X_OFFSET(3, 10.0000, 20.0000, -100.0000, 0.0000, 0.0000, 0.0000)",
      "SET_G92_OFFSET(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
      "SET_XY_ROTATION(0.0000)",
      "SELECT_PLANE(CANON_PLANE_XZ)",
      "USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 5.0000, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)",
      traverse(-10, -20, 95),
      "SELECT_TOOL(2)",
      "START_CHANGE()",
      "STOP_SPINDLE_TURNING(0)",
      "CHANGE_TOOL(2)",
      "SET_SPINDLE_SPEED(0, 1200.0000)",
      "START_SPINDLE_COUNTERCLOCKWISE(0)",
      "WAIT_SPINDLE_AT_SPEED(0)",
      "MIST_ON()",
      "FLOOD_ON()",
      "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.050000)",
      "SET_NAIVECAM_TOLERANCE(0.0500)",
      "SET_FEED_MODE(0, 0)",
      "SET_FEED_RATE(250.0000)",
      traverse(1, 2, 95),
      traverse(1, 2, 8),
      feed(1, 2, 3),
      feed(5, 2, 3)};
  const std::vector<std::string> calls = run(program, from(11));
  ASSERT_GE(calls.size(), expected.size());
  EXPECT_EQ(std::vector<std::string>(calls.begin(), calls.begin() + static_cast<long>(expected.size())), expected);

  // The tool already in the spindle is not changed again.
  CanonSetup holding = from(11);
  holding.from_line->tool_in_spindle = 2;
  const std::vector<std::string> kept = run(program, holding);
  EXPECT_EQ(std::count(kept.begin(), kept.end(), "CHANGE_TOOL(2)"), 0);
  EXPECT_EQ(kept.size(), calls.size() - 4);
}

TEST(CanonRunFromLine, InchesOffsetsAndG92AreMadeInTheProgramsUnits) {
  const std::string program =
      "G20 G17\n"
      "G10 L2 P2 X1 Y2 Z-3\n"
      "G55\n"
      "G0 X1 Y1 Z0.5\n"
      "G92 X0 Y0\n"
      "S500 M3\n"
      "G1 X1 F10\n"  // 7
      "M2\n";
  const std::vector<std::string> calls = run(program, from(7));
  ASSERT_GT(calls.size(), 20u);
  EXPECT_EQ(calls[1], "USE_LENGTH_UNITS(CANON_UNITS_INCHES)");
  EXPECT_EQ(calls[2], "SET_G5X_OFFSET(2, 1.0000, 2.0000, -3.0000, 0.0000, 0.0000, 0.0000)");
  EXPECT_EQ(calls[3], "SET_G92_OFFSET(1.0000, 1.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
  EXPECT_EQ(calls[5], "SELECT_PLANE(CANON_PLANE_XY)");
  EXPECT_NE(std::find(calls.begin(), calls.end(), "START_SPINDLE_CLOCKWISE(0)"), calls.end());
  EXPECT_NE(std::find(calls.begin(), calls.end(), "MIST_OFF()"), calls.end());
  // No feed rate before line 7 (its own F comes with it): down at rapid,
  // to where the full run is (G92 made it X0 Y0).
  const auto first_feed = std::find(calls.begin(), calls.end(), "SET_FEED_RATE(0.0000)");
  ASSERT_NE(first_feed, calls.end());
  EXPECT_EQ(*(first_feed + 1), traverse(0, 0, 3));  // clearance: machine 0 = program 3 inches
  EXPECT_EQ(*(first_feed + 2), traverse(0, 0, 0.5));
  EXPECT_EQ(*(first_feed + 3), "SET_FEED_RATE(10.0000)");
}

TEST(CanonRunFromLine, ApproachIsZUpThenXyThenDownAtRapidThenFeed) {
  const std::string program = "F300\nG0 X40 Y30 Z-20\nG1 X50\nM2\n";
  CanonSetup setup = from(3);
  setup.from_line->machine_position_mm = {-100.0, 80.0, -150.0};
  setup.from_line->clearance_z_mm = -10.0;
  setup.from_line->approach_mm = 3.0;
  const std::vector<std::string> calls = run(program, setup);
  std::vector<std::string> moves;
  for (const std::string& c : calls)
    if (c.rfind("STRAIGHT_", 0) == 0) moves.push_back(c);
  const std::vector<std::string> expected = {traverse(-100, 80, -10),  // Z alone, where the machine is
                                             traverse(40, 30, -10),    // XY at the clearance
                                             traverse(40, 30, -17),    // down at rapid to 3 mm above
                                             feed(40, 30, -20),        // the rest at F300
                                             feed(50, 30, -20)};       // line 3
  EXPECT_EQ(moves, expected);

  // A machine standing higher than the clearance is not moved down first.
  setup.from_line->machine_position_mm = {0.0, 0.0, -5.0};
  EXPECT_EQ(run(program, setup)[7], traverse(0, 0, -5));
  // An approach height longer than the way down: all of it at the feed rate.
  setup.from_line->approach_mm = 1000.0;
  const std::vector<std::string> fed = run(program, setup);
  auto xy = std::find(fed.begin(), fed.end(), traverse(40, 30, -5));
  ASSERT_NE(xy, fed.end());
  EXPECT_EQ(*(xy + 1), feed(40, 30, -20));
  EXPECT_EQ(*(xy + 2), feed(50, 30, -20));
  // No approach height: all of it at rapid.
  setup.from_line->approach_mm = 0.0;
  const std::vector<std::string> rapid = run(program, setup);
  xy = std::find(rapid.begin(), rapid.end(), traverse(40, 30, -5));
  ASSERT_NE(xy, rapid.end());
  EXPECT_EQ(*(xy + 1), traverse(40, 30, -20));
  EXPECT_EQ(*(xy + 2), feed(50, 30, -20));
  // A start point above the clearance: the tool travels at its height and does not go down.
  const std::vector<std::string> high = run("G0 X1 Y1 Z20\nG0 X2\nM2\n", from(2));
  const std::vector<std::string> expected_high = {traverse(0, 0, 20), traverse(1, 1, 20), traverse(2, 1, 20)};
  std::vector<std::string> high_moves;
  for (const std::string& c : high)
    if (c.rfind("STRAIGHT_", 0) == 0) high_moves.push_back(c);
  EXPECT_EQ(high_moves, expected_high);
}

TEST(CanonRunFromLine, ParametersAndLoopsBeforeTheLineAreEvaluated) {
  const std::string program =
      "#1 = 0\n"                       // 1
      "o100 while [#1 lt 3]\n"         // 2
      "  G0 X[#1 * 10] Y0 Z-1\n"       // 3
      "  #1 = [#1 + 1]\n"              // 4
      "o100 endwhile\n"                // 5
      "G0 X[#1 * 100]\n"               // 6
      "M2\n";
  std::vector<std::string> calls = run(program, from(6));
  // The loop ran three times, silently: the tool is at X20, the counter 3.
  const std::vector<std::string> tail(calls.end() - static_cast<long>(kEnd.size()) - 3, calls.end());
  EXPECT_EQ(tail[0], traverse(20, 0, -1));  // the approach's last move
  EXPECT_EQ(tail[1], traverse(300, 0, -1));
  // The second pass of line 3: the first pass ran silently, two run.
  CanonSetup second = from(3);
  second.from_line->pass = 2;
  calls = run(program, second);
  std::vector<std::string> moves;
  for (const std::string& c : calls)
    if (c.rfind("STRAIGHT_", 0) == 0) moves.push_back(c);
  const std::vector<std::string> expected = {traverse(0, 0, 0), traverse(0, 0, 0), traverse(0, 0, -1),
                                             traverse(10, 0, -1), traverse(20, 0, -1), traverse(300, 0, -1)};
  EXPECT_EQ(moves, expected);
  second.from_line->pass = 4;
  const GcodeError e = refusal(program, second);
  EXPECT_EQ(e.line, 3);
  EXPECT_NE(e.message.find("runs only 3 times, not 4"), std::string::npos) << e.message;
}

TEST(CanonRunFromLine, CallsBeforeTheLineAreSilentButOffsetsApply) {
  const std::string program =
      "(LOGOPEN,probe.txt)\n"     // 1
      "(MSG,load the part)\n"     // 2
      "M0\n"                      // 3
      "M1\n"                      // 4
      "T3 M6\n"                   // 5
      "G4 P2\n"                   // 6
      "T4 M6\n"                   // 7
      "G0 X5 Y5 Z-2\n"            // 8
      "G92 X0 Y0\n"               // 9
      "M70\n"                     // 10
      "G20\n"                     // 11
      "(LOG,here)\n"              // 12
      "M72\n"                     // 13
      "G0 X1\n"                   // 14
      "M2\n";
  const std::vector<std::string> calls = run(program, from(12));
  for (const char* silent : {"PROGRAM_STOP()", "OPTIONAL_PROGRAM_STOP()", "DWELL(2.0000)", "CHANGE_TOOL(3)",
                             "MESSAGE(\"load the part\")", "LOGOPEN(\"probe.txt\")"})
    EXPECT_EQ(std::count(calls.begin(), calls.end(), silent), 0) << silent;
  EXPECT_EQ(std::count(calls.begin(), calls.end(), "CHANGE_TOOL(4)"), 1);
  // The log opened before the line is appended to, not reopened empty.
  EXPECT_EQ(std::count(calls.begin(), calls.end(), "LOGAPPEND(\"probe.txt\")"), 1);
  EXPECT_EQ(std::count(calls.begin(), calls.end(), "LOG(\"here\")"), 1);
  // G92 applied: shown in the program's units (inches at line 12) and moving
  // the start point; M72 restores the millimetres M70 saved before the line.
  EXPECT_NE(std::find(calls.begin(), calls.end(), "SET_G92_OFFSET(0.1969, 0.1969, 0.0000, 0.0000, 0.0000, 0.0000)"),
            calls.end());
  EXPECT_NE(std::find(calls.begin(), calls.end(), "USE_LENGTH_UNITS(CANON_UNITS_MM)"), calls.end());
  EXPECT_NE(std::find(calls.begin(), calls.end(), traverse(1, 0, -2)), calls.end());
}

TEST(CanonRunFromLine, RefusesStartsThatCannotBeSafeOrDoNotExist) {
  const std::string plain = "G0 X1\nG0 X2\nM2\n";
  GcodeError e = refusal(plain, from(9));
  EXPECT_EQ(e.line, 9);
  EXPECT_NE(e.message.find("the program has lines 1 to 4"), std::string::npos) << e.message;
  e = refusal(plain, from(4));  // after M2
  EXPECT_EQ(e.line, 4);
  EXPECT_NE(e.message.find("never runs it"), std::string::npos) << e.message;
  e = refusal("o1 if [0]\nG0 X1\no1 endif\nM2\n", from(2));
  EXPECT_NE(e.message.find("never runs it"), std::string::npos) << e.message;

  const std::string sub = "o<p> sub\nG0 X#1\no<p> endsub\no<p> call [4]\nM2\n";
  for (int line : {1, 2, 3}) {
    e = refusal(sub, from(line));
    EXPECT_EQ(e.line, line);
    EXPECT_NE(e.message.find("definition of subroutine o<p> (lines 1 to 3)"), std::string::npos) << e.message;
  }
  EXPECT_FALSE(interpret_canon(sub, from(4)).error);  // the call itself is a start

  const std::string comp = "F100\nG0 X0 Y0\nG41 D2\nG1 X10\nG1 Y10\nG40\nG0 X20\nM2\n";
  e = refusal(comp, from(5));
  EXPECT_EQ(e.line, 5);
  EXPECT_NE(e.message.find("cutter radius compensation (line 3)"), std::string::npos) << e.message;
  EXPECT_FALSE(interpret_canon(comp, from(7)).error);  // after the G40
  EXPECT_FALSE(interpret_canon(comp, from(3)).error);  // at the G41 line itself: compensation starts after the approach

  // A touch-off from a probe: the offset comes from where it tripped (canon_run_from_line.cpp; more below).
  const std::string probe = "F50\nG38.3 Z-10\nG10 L20 P1 Z0\nG0 X1\nM2\n";
  e = refusal(probe, from(4));
  EXPECT_EQ(e.line, 3);
  EXPECT_NE(e.message.find("cannot run from line 4: G10 L20 sets an offset from the Z position where the probe "
                           "(G38.x) at line 2 tripped"),
            std::string::npos)
      << e.message;
  EXPECT_FALSE(interpret_canon(probe, from(2)).error);

  CanonSetup bad = from(1);
  bad.from_line->pass = 0;
  EXPECT_NE(refusal(plain, bad).message.find("pass"), std::string::npos);
  bad = from(1);
  bad.from_line->approach_mm = -1.0;
  EXPECT_NE(refusal(plain, bad).message.find("approach"), std::string::npos);
}

// Past a probe (G38.x) that the run skips, its result and the axes it
// moved are unknown: a start is fine once every such axis was given again
// absolutely and nothing reads the result; else refused, naming the line
// that needs the unknown and the probe's line.
TEST(CanonRunFromLine, PastASkippedProbeOnlyWhatDoesNotDependOnItRuns) {
  // Z probed, then Z given again: from line 4 on the calls are the full run's.
  const std::string regiven = "F50\nG38.2 Z-10\nG0 Z5\nG0 X1\nG1 Y2\nM2\n";
  const std::vector<std::string> full = run(regiven, with_tools());
  const std::vector<std::string> part = run(regiven, from(4));
  ASSERT_GE(part.size(), 2u);
  EXPECT_EQ(std::vector<std::string>(part.end() - 2, part.end()), std::vector<std::string>(full.end() - 2, full.end()));
  EXPECT_NE(std::find(part.begin(), part.end(), traverse(1, 0, 5)), part.end());
  EXPECT_EQ(std::find_if(part.begin(), part.end(), [](const std::string& c) { return c.rfind("STRAIGHT_PROBE", 0) == 0; }),
            part.end())
      << "the skipped probe makes no call";

  // Z never given again: where the tool is at the start depends on the trip.
  GcodeError e = refusal("F50\nG38.2 Z-10\nG0 X1\nG0 X2\nM2\n", from(4));
  EXPECT_EQ(e.line, 4);
  EXPECT_NE(e.message.find("cannot run from line 4: the Z position there comes from where the probe (G38.x) at line 2 "
                           "tripped"),
            std::string::npos)
      << e.message;
  // An incremental Z move keeps it unknown; an absolute one in G53 or a G28 ends it.
  EXPECT_NE(refusal("F50\nG38.2 Z-10\nG91 G0 Z5\nG90\nG0 X1\nM2\n", from(5)).message.find("Z position there"),
            std::string::npos);
  EXPECT_FALSE(interpret_canon("F50\nG38.2 Z-10\nG53 G0 Z0\nG0 X1\nM2\n", from(4)).error);
  EXPECT_FALSE(interpret_canon("F50\nG38.2 X-10\nG28\nG0 Z1\nM2\n", from(4)).error);

  // The result read after the start: refused where it is read.
  e = refusal("F50\nG38.2 Z-10\nG0 Z5\nG0 X1\nG0 Z[#5063 + 1]\nM2\n", from(4));
  EXPECT_EQ(e.line, 5);
  EXPECT_NE(e.message.find("#5063 is the result of the probe (G38.x) at line 2, which the run from line 4 skips; start "
                           "at or before line 2"),
            std::string::npos)
      << e.message;
  // ... and before it, as the position (#5422, #<_z>) while Z is unknown.
  e = refusal("F50\nG38.2 Z-10\n#1 = #<_z>\nG0 Z5\nG0 X1\nM2\n", from(5));
  EXPECT_EQ(e.line, 3);
  EXPECT_NE(e.message.find("#<_z> is the Z position where the probe (G38.x) at line 2 tripped"), std::string::npos)
      << e.message;
  EXPECT_EQ(refusal("F50\nG38.2 Z-10\n#1 = #5422\nG0 Z5\nG0 X1\nM2\n", from(5)).line, 3);
  // G92 and G28.1 store the unknown position.
  EXPECT_EQ(refusal("F50\nG38.2 Z-10\nG92 Z0\nG0 Z5\nG0 X1\nM2\n", from(5)).line, 3);
  EXPECT_EQ(refusal("F50\nG38.2 Z-10\nG28.1\nG0 Z5\nG0 X1\nM2\n", from(5)).line, 3);
  // An axis the probe did not move stays known: a G92 of X is fine.
  EXPECT_FALSE(interpret_canon("F50\nG38.2 Z-10\nG92 X0\nG0 Z5\nG0 X1\nM2\n", from(5)).error);
  // The result assigned again, or a probe that runs after the start, is known.
  EXPECT_FALSE(interpret_canon("F50\nG38.2 Z-10\n#5063 = 0\nG0 Z5\nG0 X1\nG0 Z[#5063 + 1]\nM2\n", from(5)).error);
  EXPECT_FALSE(
      interpret_canon("F50\nG38.2 Z-10\nG0 Z5\nG0 X1\nG38.2 Z-10\nG0 Z[#5063 + 1]\nM2\n", from(4)).error);
  // Without a run from line nothing of this applies.
  EXPECT_FALSE(interpret_canon("F50\nG38.2 Z-10\nG10 L20 P1 Z0\nG0 X[#5061]\nM2\n", with_tools()).error);
}

TEST(CanonRunFromLine, CannedCycleLineIsAStart) {
  const std::string program = "F100\nG0 X0 Y0 Z5\nG99 G81 X10 Y10 Z-2 R1\nX20\nX30\nG80\nM2\n";
  const std::vector<std::string> calls = run(program, from(4));
  std::vector<std::string> moves;
  for (const std::string& c : calls)
    if (c.rfind("STRAIGHT_", 0) == 0) moves.push_back(c);
  // The hole before ran silently and left the tool at R above it (G99);
  // the clearance (machine Z 0) is below R here, so the tool travels at R.
  const std::vector<std::string> expected = {traverse(0, 0, 1),   traverse(10, 10, 1), traverse(20, 10, 1),
                                             feed(20, 10, -2),    traverse(20, 10, 1), traverse(30, 10, 1),
                                             feed(30, 10, -2),    traverse(30, 10, 1)};
  EXPECT_EQ(moves, expected);
}

// --- The oracle: the tail of a full run ------------------------------------

// The line with a message at its start, so the full run shows where it
// began; nullopt for lines a comment cannot join ('%', '/').
std::optional<std::string> marked(const std::string& program, int line) {
  std::istringstream in(program);
  std::string out, text;
  bool ok = true;
  for (int n = 1; std::getline(in, text); ++n) {
    if (n == line) {
      const std::size_t first = text.find_first_not_of(" \t");
      if (first != std::string::npos && (text[first] == '%' || text[first] == '/')) ok = false;
      const std::size_t semicolon = text.find(';');
      const std::size_t at = semicolon == std::string::npos ? text.size() : semicolon;
      text.insert(at, " (MSG,@start@) ");
    }
    out += text + "\n";
  }
  return ok ? std::optional<std::string>(out) : std::nullopt;
}

bool is_message_marker(const CanonCall& c) { return c.text == "MESSAGE(\"@start@) \")" || c.text == "MESSAGE(\"@start@\")"; }

// Where the machine is after calls [0, end), in machine coordinates (mm),
// read from the calls alone: the last straight move's end with the units
// and offsets in force when it was made; nullopt after a move whose end the
// call does not give (arcs, splines, probes, taps).
std::optional<std::array<double, 3>> machine_after(const std::vector<CanonCall>& calls, std::size_t end) {
  double scale = 1.0;
  std::array<double, 3> g5x{}, g92{}, tool{};
  bool length_changed = false;  // a tool length offset since the last move
  std::optional<std::array<double, 3>> at = std::array<double, 3>{};  // a run starts at machine 0 0 0
  const auto numbers = [](const std::string& text) {
    std::vector<double> v;
    std::string s = text.substr(text.find('(') + 1);
    for (char& c : s)
      if (c == ',' || c == ')') c = ' ';
    std::istringstream in(s);
    for (double x; in >> x;) v.push_back(x);
    return v;
  };
  for (std::size_t k = 0; k < end; ++k) {
    const std::string& t = calls[k].text;
    const auto starts = [&t](const char* p) { return t.rfind(p, 0) == 0; };
    if (starts("USE_LENGTH_UNITS(")) {
      scale = t.find("INCHES") != std::string::npos ? 25.4 : 1.0;
    } else if (starts("SET_G5X_OFFSET(")) {
      const auto v = numbers(t);
      for (std::size_t a = 0; a < 3; ++a) g5x[a] = v[a + 1] * scale;
    } else if (starts("SET_G92_OFFSET(") || starts("USE_TOOL_LENGTH_OFFSET(")) {
      const auto v = numbers(t);
      for (std::size_t a = 0; a < 3; ++a) (starts("SET_G92") ? g92 : tool)[a] = v[a] * scale;
      length_changed |= starts("USE_TOOL");
    } else if (starts("CHANGE_TOOL(") && length_changed) {
      // rs274 takes its position back at a tool change without a tool
      // length offset applied since the last move: the interpreter's
      // point is no longer the machine's, and the approach goes to the
      // interpreter's (the tail's moves start from it).
      at.reset();
    } else if (starts("PROGRAM_STOP()") && k >= 2 && calls[k - 1].text == "STOP_SPINDLE_TURNING(0)" &&
               calls[k - 2].text.rfind("DWELL(", 0) == 0) {
      // G88's stop: the operator retracts the tool by hand, the calls do
      // not say where to; the interpreter takes it to be at the clearance,
      // and the approach goes there (the tail's moves start from it).
      at.reset();
    } else if (starts("STRAIGHT_TRAVERSE(") || starts("STRAIGHT_FEED(")) {
      const auto v = numbers(t);
      length_changed = false;
      at = std::array<double, 3>{};
      for (std::size_t a = 0; a < 3; ++a) (*at)[a] = v[a] * scale + g5x[a] + g92[a] + tool[a];
    } else if (starts("ARC_FEED(") || starts("NURBS_FEED(") || starts("STRAIGHT_PROBE(") || starts("RIGID_TAP(")) {
      at.reset();
    }
  }
  return at;
}

struct Checked {
  int started = 0, refused = 0;
};

// Under a sanitizer every 3rd line is a start (each start runs the program twice): the checks below are
// per start; the counts the tests expect are a quarter of the Release build's.
constexpr int kLineStride = tnv::test::kSanitizedBuild ? 3 : 1;
constexpr int kExpectedCountDivisor = tnv::test::kSanitizedBuild ? 4 : 1;

// Every line of `program` (of a long one, every step-th) as a start: refused for a reason the docs give, or
// the calls from the start marker on equal the full run's from its pass.
void check_every_line(const std::string& name, const std::string& program, const CanonSetup& base, Checked& checked) {
  const int line_count = static_cast<int>(std::count(program.begin(), program.end(), '\n'));
  // A long program: 80 starts spread over it (27 under a sanitizer).
  const int step = std::max(kLineStride, line_count / (80 / kLineStride));
  for (int line = 1; line <= line_count; line += step) {
    const std::optional<std::string> text = marked(program, line);
    if (!text) continue;
    const CanonResult full = interpret_canon(*text, base);
    if (full.error) continue;  // the program (as marked) is refused whole; nothing to compare
    CanonSetup setup = base;
    setup.from_line = RunFromLine{};
    setup.from_line->line = line;
    const CanonResult part = interpret_canon(*text, setup);
    std::vector<std::size_t> marks;
    for (std::size_t k = 0; k < full.calls.size(); ++k)
      if (is_message_marker(full.calls[k])) marks.push_back(k);
    if (part.error) {
      ++checked.refused;
      const std::string& why = part.error->message;
      // A skipped probe's result is refused where it is used, which may be before or after N.
      if (why.find("probe (G38.x) at line") == std::string::npos) {
        EXPECT_EQ(part.error->line, line) << name;
      }
      const bool known = why.find("cutter radius compensation") != std::string::npos ||
                         why.find("probe (G38.x) at line") != std::string::npos ||
                         why.find("definition of subroutine") != std::string::npos ||
                         (why.find("never runs it") != std::string::npos && marks.empty());
      EXPECT_TRUE(known) << name << " line " << line << ": " << why;
      continue;
    }
    ++checked.started;
    ASSERT_FALSE(marks.empty()) << name << " line " << line << " started but the full run never ran it";
    const auto first_mark = std::find_if(part.calls.begin(), part.calls.end(), is_message_marker);
    ASSERT_NE(first_mark, part.calls.end()) << name << " line " << line;
    const std::vector<CanonCall> tail(first_mark, part.calls.end());
    const std::vector<CanonCall> expected(full.calls.begin() + static_cast<long>(marks[0]), full.calls.end());
    ASSERT_EQ(tail.size(), expected.size()) << name << " line " << line;
    for (std::size_t k = 0; k < tail.size(); ++k) {
      ASSERT_EQ(tail[k].text, expected[k].text) << name << " line " << line << " call " << k;
      ASSERT_EQ(tail[k].line, expected[k].line) << name << " line " << line << " call " << k;
    }
    // The approach ends where the full run's tool is (machine coordinates).
    const auto full_at = machine_after(full.calls, marks[0]);
    const auto part_at = machine_after(part.calls, static_cast<std::size_t>(first_mark - part.calls.begin()));
    if (full_at && part_at) {
      for (std::size_t a = 0; a < 3; ++a)
        EXPECT_NEAR((*part_at)[a], (*full_at)[a], 3e-3) << name << " line " << line << " axis " << a;
    }
  }
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(CanonRunFromLine, EveryLineOfTheOracleProgramsAndTestPiecesContinuesAsTheFullRun) {
  Checked checked;
  std::vector<std::filesystem::path> files;
  for (const char* dir : {"/tools/gcode/oracle/programs", "/tests/data/paths"})
    for (const auto& entry : std::filesystem::directory_iterator(std::string(TNV_SOURCE_DIR) + dir))
      if (entry.path().extension() == ".ngc") files.push_back(entry.path());
  ASSERT_GE(files.size(), 11u);
  std::sort(files.begin(), files.end());
  for (const auto& path : files) check_every_line(path.filename().string(), read_text(path), with_tools(), checked);
  // Most lines are starts; the compensated contours and the lines after a probe that need it are refused.
  std::printf("[from-line] oracle programs and test pieces: %d starts, %d refused\n", checked.started, checked.refused);
  EXPECT_GT(checked.started, 300 / kExpectedCountDivisor);
  EXPECT_GT(checked.refused, 50 / kExpectedCountDivisor);
}

// Small programs from a seeded generator: loops, subroutine calls,
// offsets, tool changes, units, spindle, coolant, canned cycles, M70/M72.
std::string random_program(std::mt19937& rng) {
  const auto pick = [&rng](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
  const auto coordinate = [&]() { return std::to_string(pick(41) - 20) + "." + std::to_string(pick(10)); };
  std::string p = "o<step> sub\n  G91 G0 X#1\n  G1 Y#2 F[100 + #1]\n  G90\no<step> endsub\n";
  p += pick(2) ? "G21\n" : "G20\n";
  p += "#<n> = " + std::to_string(pick(4)) + "\n";
  const int lines = 8 + pick(15);
  for (int k = 0; k < lines; ++k) {
    switch (pick(14)) {
      case 0: p += "G0 X" + coordinate() + " Y" + coordinate() + " Z" + coordinate() + "\n"; break;
      case 1: p += "G1 X" + coordinate() + " Z" + coordinate() + " F" + std::to_string(50 + pick(500)) + "\n"; break;
      case 2: p += "G5" + std::to_string(4 + pick(6)) + "\n"; break;
      case 3: p += "G10 L2 P" + std::to_string(1 + pick(6)) + " X" + coordinate() + " Z" + coordinate() + "\n"; break;
      case 4: p += "T" + std::to_string(1 + pick(5)) + " M6\nG43\n"; break;
      case 5: p += "S" + std::to_string(100 * (1 + pick(60))) + (pick(2) ? " M3\n" : " M4\n"); break;
      case 6: p += pick(3) == 0 ? "M9\n" : pick(2) ? "M7\n" : "M8\n"; break;
      case 7:
        p += "o" + std::to_string(10 + k) + " while [#<n> lt " + std::to_string(2 + pick(3)) + "]\n  G1 X[#<n> * " +
             coordinate() + "] F200\n  #<n> = [#<n> + 1]\no" + std::to_string(10 + k) + " endwhile\n";
        break;
      case 8: p += "o<step> call [" + coordinate() + "] [" + coordinate() + "]\n"; break;
      case 9: p += "G92 X" + coordinate() + "\n"; break;
      case 10: p += "M70\n" + std::string(pick(2) ? "G20\n" : "G21\n") + "G18\nM72\n"; break;
      case 11: p += "G98 G81 X" + coordinate() + " Y" + coordinate() + " Z-3 R2 F90\nX" + coordinate() + "\nG80\n"; break;
      case 12: p += "G0 X[#<n> + " + coordinate() + "] Y" + coordinate() + "\n"; break;
      default: p += pick(2) ? "G64 P0.01\n" : "G61\n"; break;
    }
    if (pick(6) == 0) p += "G17\n";
  }
  p += pick(2) ? "M2\n" : "M30\n";
  return p;
}

TEST(CanonRunFromLine, RandomProgramsContinueAsTheFullRunFromEveryLine) {
  std::mt19937 rng(20261129);
  Checked checked;
  for (int seed = 0; seed < 150; ++seed) {
    const std::string program = random_program(rng);
    check_every_line("random " + std::to_string(seed) + ":\n" + program, program, with_tools(), checked);
    if (HasFatalFailure()) return;
  }
  std::printf("[from-line] 150 random programs: %d starts, %d refused\n", checked.started, checked.refused);
  EXPECT_GT(checked.started, 4000 / kExpectedCountDivisor);
  EXPECT_GT(checked.refused, 500 / kExpectedCountDivisor);
}

}  // namespace
}  // namespace tnv::gcode::run_from_line_test
