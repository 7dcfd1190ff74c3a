// tnv-hil path as a user runs it: a small program with lines and arcs on
// the emulated table, the JSON keys of docs/motion.md, the limits kept,
// the contour error in a plausible band, and clear refusals of a bad
// program (line and column) or a missing file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "tests/tools/cli_runner.hpp"

namespace tnv::test {
namespace {

std::string temp_program(const std::string& name, const std::string& text) {
  const std::filesystem::path p =
      std::filesystem::temp_directory_path() / ("tnv_path_" + std::to_string(::getpid()) + "_" + name + ".ngc");
  std::ofstream(p) << text;
  return p.string();
}

// A 10 mm square with a rounded corner and a dwell, at 5 mm/s.
constexpr const char* kSmallPiece =
    "G17 G21 G90\nG0 X5 Y0\nG1 F300 X10 Y0\nY5\nG3 X5 Y10 I-5 J0\nG1 X0 Y10\nG4 P0.05\nY0\nX5\nM2\n";

TEST(PathCli, ScoresASmallPieceWithinTheLimitsAndReportsEveryKey) {
  const std::string file = temp_program("small", kSmallPiece);
  const CliRun r = run_tnv_hil("path " + file + " --controller rdvsc --scenario no-cut --seeds 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"contour_error_max_um", "contour_error_mean_um", "contour_error_std_um",
                          "path_deviation_max_um", "accel_ratio_max", "jerk_ratio_max", "feed_ratio", "cycle_time_s",
                          "underruns", "per_seed"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["per_seed"].size(), 2u);
  EXPECT_LE(j["accel_ratio_max"].get<double>(), 1.0 + 1e-6);
  EXPECT_LE(j["jerk_ratio_max"].get<double>(), 1.0 + 1e-6);
  EXPECT_GT(j["accel_ratio_max"].get<double>(), 0.1) << "the corners did use the acceleration";
  EXPECT_LE(j["path_deviation_max_um"].get<double>(), 5.0 + 1e-6) << "the path tolerance is 5 um";
  // A real loop on a real table: not zero (quantisation alone is ~0.1 um), not a runaway.
  EXPECT_GT(j["contour_error_mean_um"].get<double>(), 0.05);
  EXPECT_LT(j["contour_error_max_um"].get<double>(), 20.0);
  EXPECT_GT(j["feed_ratio"].get<double>(), 0.3);
  EXPECT_LE(j["feed_ratio"].get<double>(), 1.0 + 1e-9) << "never faster than programmed";
  EXPECT_EQ(j["underruns"], 0);
  std::filesystem::remove(file);
}

TEST(PathCli, AProgramErrorNamesLineAndColumnAndRunsNothing) {
  const std::string file = temp_program("bad", "G21 G91\nG1 F100 X1\n  G95 G1 X2\n");
  const CliRun r = run_tnv_hil("path " + file);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("line 3, column 3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("G95"), std::string::npos) << r.err;
  std::filesystem::remove(file);
}

// The dialect with a tool table and a parameter file: G55's offset from
// the .var file, tool 4 from the .tbl (the M6 pauses, and continues after
// --resume-after-s), the spindle sent, coolant counted and not sent; the report
// has lines run, segments, tool changes, the pause and the programmed cycle time.
TEST(PathCli, TakesAToolTableAndAVarFileAndReportsLinesSegmentsToolChangesAndCycleTime) {
  const std::string tbl = temp_program("tools", "T4 P4 Z20 D3\n");
  const std::string var = temp_program("offsets", "5241 1\n5242 2\n");  // G55 at X1 Y2
  const std::string file = temp_program(
      "dialect", "G55\nT4 M6\nM4 S500 M7\nG0 X0 Y0\n#1 = 0\no1 while [#1 LT 2]\n  G91 G1 X4 F600\n  G90\n"
                 "  #1 = [#1 + 1]\no1 endwhile\nG4 P0.1\nM2\n");
  const CliRun r = run_tnv_hil("path " + file + " --tool-table " + tbl + " --var-file " + var + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["tool_changes"], 1);
  EXPECT_EQ(j["spindle_starts"], 1);
  EXPECT_EQ(j["spindle_commands"], 3) << "M6's stop, M4 S500, M2's stop";
  EXPECT_EQ(j["coolant_starts_not_sent"], 1);
  // Five lines, two passes of the loop's five lines, the while line once more (false), G4 and M2.
  EXPECT_EQ(j["lines_run"], 5 + 2 * 5 + 1 + 2);
  const int segments = j["segments"].get<int>();
  // M6's spindle stop and pause, M4 S500, the rapid to G55's origin (none if the table stands there), two 4 mm
  // feeds at 10 mm/s, the dwell, M2's spindle stop.
  EXPECT_TRUE(segments == 7 || segments == 8) << segments;
  EXPECT_EQ(j["program_pauses"], 1);
  ASSERT_EQ(j["pauses"].size(), 1u) << j.dump();
  EXPECT_EQ(j["pauses"][0]["line"], 2);
  EXPECT_EQ(j["pauses"][0]["reason"], "tool change (M6)");
  EXPECT_EQ(j["pauses"][0]["tool"], 4);
  EXPECT_GE(j["pauses"][0]["paused_s"].get<double>(), 1.0 - 1e-9) << "the default --resume-after-s";
  EXPECT_GE(j["programmed_time_s"].get<double>(), 8.0 / 10.0 + 0.1 - 1e-9);
  EXPECT_EQ(j["cycle_time_s"].is_number(), true);
  // Without the tool table, tool 4 is unknown: a program error, nothing run.
  const CliRun no_tools = run_tnv_hil("path " + file + " --var-file " + var);
  EXPECT_EQ(no_tools.exit_code, 2);
  EXPECT_NE(no_tools.err.find("requested tool 4 not found"), std::string::npos) << no_tools.err;
  for (const std::string& f : {tbl, var, file}) std::filesystem::remove(f);
}

// The block delete switch reaches the interpreter: on (the default) the
// slashed feed is skipped, off it runs; a value other than on/off is refused.
TEST(PathCli, BlockDeleteSwitchDecidesWhetherTheSlashedLineRuns) {
  const std::string file = temp_program("blockdelete", "G21 G90 F600\nG1 X2\n/G1 X2 Y2\nG1 X0 Y0\nM2\n");
  const CliRun on = run_tnv_hil("path " + file + " --json");
  ASSERT_EQ(on.exit_code, 0) << on.err;
  const CliRun off = run_tnv_hil("path " + file + " --block-delete off --json");
  ASSERT_EQ(off.exit_code, 0) << off.err;
  const auto j_on = nlohmann::json::parse(on.out);
  const auto j_off = nlohmann::json::parse(off.out);
  EXPECT_EQ(j_off["segments"].get<int>(), j_on["segments"].get<int>() + 1);
  // From X2 back to the origin: straight (2 mm), or up to X2 Y2 and down the diagonal (2 + 2.83 mm).
  EXPECT_NEAR(j_off["programmed_length_mm"].get<double>() - j_on["programmed_length_mm"].get<double>(),
              std::sqrt(8.0), 1e-9);
  const CliRun bad = run_tnv_hil("path " + file + " --block-delete maybe");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--block-delete"), std::string::npos) << bad.err;
  std::filesystem::remove(file);
}

// M0 pauses, M1 only with the optional stop switch on; each pause is
// continued after --resume-after-s and printed with its line.
TEST(PathCli, PausesAtM0AndM1AndContinuesAfterTheResumeTime) {
  const std::string file = temp_program("pauses", "G21 G91 F600\nG1 X2\nM0\nG1 Y2\nM1\nG1 X-2\nM2\n");
  const CliRun on = run_tnv_hil("path " + file + " --resume-after-s 0.25 --json");
  ASSERT_EQ(on.exit_code, 0) << on.err;
  const auto j_on = nlohmann::json::parse(on.out);
  ASSERT_EQ(j_on["pauses"].size(), 2u) << j_on.dump();
  EXPECT_EQ(j_on["pauses"][0]["line"], 3);
  EXPECT_EQ(j_on["pauses"][0]["reason"], "program stop (M0)");
  EXPECT_EQ(j_on["pauses"][1]["line"], 5);
  EXPECT_NEAR(j_on["pauses"][1]["paused_s"].get<double>(), 0.25, 1e-9);
  const CliRun off = run_tnv_hil("path " + file + " --optional-stop off --resume-after-s 0.25");
  ASSERT_EQ(off.exit_code, 0) << off.err;
  EXPECT_NE(off.out.find("paused at line 3: program stop (M0)"), std::string::npos) << off.out;
  EXPECT_EQ(off.out.find("line 5"), std::string::npos) << "M1 paused with the switch off: " << off.out;
  EXPECT_NE(off.out.find("1 optional stop skipped"), std::string::npos) << off.out;
  const CliRun bad = run_tnv_hil("path " + file + " --optional-stop maybe");
  EXPECT_EQ(bad.exit_code, 2);
  std::filesystem::remove(file);
}

// --from-line N runs the program from line N (with --from-pass K for a line in a loop); the companions need it.
TEST(PathCli, RunsFromALine) {
  const std::string file = temp_program("fromline", "G21 G91 F600\nG1 X2\nG1 Y2\nG1 X-2\nM2\n");
  const CliRun r = run_tnv_hil("path " + file + " --from-line 3 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  // The spindle as line 3 has it (off: a stop), Z up to the clearance (machine Z 0) from where it homed
  // (25 mm below), across to the end of line 2, down at rapid and the last 5 mm at the feed, then lines 3 and 4.
  EXPECT_EQ(j["segments"], 7) << j.dump();
  EXPECT_EQ(j["spindle_commands"], 1);
  EXPECT_NEAR(j["programmed_length_mm"].get<double>(), 25.0 + 2.0 + 25.0 + 2.0 + 2.0, 1e-9);
  const CliRun alone = run_tnv_hil("path " + file + " --from-pass 2");
  EXPECT_EQ(alone.exit_code, 2) << "--from-pass without --from-line";
  EXPECT_NE(alone.err.find("--from-line"), std::string::npos) << alone.err;
  std::filesystem::remove(file);
}

TEST(PathCli, RefusesAMissingFileAndAPlotIntoAMissingDirectory) {
  EXPECT_EQ(run_tnv_hil("path /nonexistent/piece.ngc").exit_code, 2);
  const std::string file = temp_program("plotdir", kSmallPiece);
  const CliRun r = run_tnv_hil("path " + file + " --plot /nonexistent/dir/p.svg");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("directory /nonexistent/dir does not exist"), std::string::npos) << r.err;
  std::filesystem::remove(file);
}

TEST(PathCli, WritesThePlot) {
  const std::string file = temp_program("plot", kSmallPiece);
  const std::string svg = file + ".svg";
  const CliRun r = run_tnv_hil("path " + file + " --plot " + svg);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(svg);
  const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(content.find("<svg"), std::string::npos);
  EXPECT_NE(content.find("contour error"), std::string::npos);
  std::filesystem::remove(file);
  std::filesystem::remove(svg);
}

// --hold-at / --resume-at hold the feed on the emulated machine and say so:
// per hold the path speed when it came, the time to rest and the spindle
// while held; the held time is in the cycle. Bad pairs are refused, exit 2.
TEST(PathCli, HoldAtAndResumeAtHoldTheFeedAndReportEachHold) {
  const std::string file = temp_program("hold", "G21 G91\nM3 S1000\nG1 X40 F1200\nM5\nM2\n");
  const CliRun plain = run_tnv_hil("path " + file + " --json");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const CliRun r = run_tnv_hil("path " + file + " --hold-at 1.2 --resume-at 1.7 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["holds"].size(), 1u) << j.dump();
  EXPECT_EQ(j["holds"][0]["applied"], true);
  EXPECT_NEAR(j["holds"][0]["path_speed_at_hold_mm_s"].get<double>(), 20.0, 1e-9);
  EXPECT_GT(j["holds"][0]["stopped_after_s"].get<double>(), 0.0);
  EXPECT_GT(j["holds"][0]["spindle_rpm_min_held"].get<double>(), 900.0) << "the spindle keeps turning";
  EXPECT_NEAR(j["held_s"].get<double>(), 0.5, 1e-9);
  EXPECT_NEAR(j["cycle_time_s"].get<double>(), nlohmann::json::parse(plain.out)["cycle_time_s"].get<double>() + 0.5,
              0.002);
  const CliRun text = run_tnv_hil("path " + file + " --hold-at 1.2 --resume-at 1.7");
  EXPECT_NE(text.out.find("feed hold 1.200-1.700 s: path speed 20.000 mm/s at the hold"), std::string::npos)
      << text.out;
  const CliRun unpaired = run_tnv_hil("path " + file + " --hold-at 1");
  EXPECT_EQ(unpaired.exit_code, 2);
  EXPECT_NE(unpaired.err.find("come in pairs"), std::string::npos) << unpaired.err;
  const CliRun backwards = run_tnv_hil("path " + file + " --hold-at 1 --resume-at 2 --hold-at 1.5 --resume-at 3");
  EXPECT_EQ(backwards.exit_code, 2);
  EXPECT_NE(backwards.err.find("before the previous --resume-at 2"), std::string::npos) << backwards.err;
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace tnv::test
