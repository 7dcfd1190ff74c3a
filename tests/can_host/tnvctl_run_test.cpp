// `tnvctl run`: the emulated run of a test piece scores within 10 % of an
// independent in-process run of the same firmware (no CAN: segments pushed
// straight into the tick task), with no underrun; a bad program is refused
// naming line and column before anything is sent; Ctrl-C stops on the
// path and exits 1; the help reads like a manual page.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "emulator/scenario_file.hpp"
#include "tests/can_host/tnvctl_runner.hpp"
#include "tests/tools/gcode/test_piece_path.hpp"
#include "tools/hil/hil_firmware_config.hpp"
#include "tools/hil/hil_rig.hpp"
#include "tools/score/path_score.hpp"

namespace tnv {
namespace {

using test::ToolRun;

// The same firmware and table in-process: enable, push the parsed program
// into the tick task as fast as its queue takes it, record every tick.
hil::PathScore in_process_score(const std::string& piece, std::uint64_t& underruns) {
  const emu::Scenario scenario = *emu::builtin_scenario("no-cut");
  std::string error;
  auto rig = hil::HilRig::create(scenario, hil::firmware_config_for(scenario, fw::default_firmware_config()),
                                 fw::ControllerKind::rdvsc, error);
  EXPECT_TRUE(rig) << error;
  rig->home();
  EXPECT_EQ(rig->task.hold_position(), fw::CommandStatus::ok);
  for (int k = 0; k < 20; ++k) rig->tick();
  gcode::GcodeOptions g;
  g.start_mm = rig->task.next_segment_start_mm();
  g.limits = fw::path_limits(rig->task.config());
  const gcode::GcodeResult parsed = gcode::parse_gcode_file(gcode::test::test_piece_path(piece.c_str()), g);
  EXPECT_FALSE(parsed.error);
  const std::vector<fw::motion::Segment>& segments = parsed.program.segments;
  std::vector<hil::PathSample> samples;
  const auto record = [&] {
    const fw::TickRecord& r = rig->task.last_record();
    samples.push_back({{r.axis[0].position_mm, r.axis[1].position_mm}, {r.axis[0].reference_mm, r.axis[1].reference_mm}});
  };
  record();
  std::size_t next = 0;
  const std::uint64_t underruns_before = rig->task.motion().stats().underruns;
  for (int k = 0; k < 2'000'000; ++k) {
    while (next < segments.size() && rig->task.motion().free_slots() > 0) {
      fw::motion::SegmentRefusal why{};
      EXPECT_EQ(rig->task.push_segment(segments[next], why), fw::CommandStatus::ok) << fw::motion::to_string(why);
      ++next;
      if (next == segments.size()) rig->task.end_program();
    }
    rig->tick();
    record();
    if (next == segments.size() && rig->task.state() == fw::MotionState::holding) break;
  }
  for (int k = 0; k < 20; ++k) {
    rig->tick();
    record();
  }
  underruns = rig->task.motion().stats().underruns - underruns_before;
  EXPECT_EQ(rig->task.state(), fw::MotionState::holding);
  return hil::score_path(parsed.program, samples, g.limits);
}

TEST(TnvctlRun, EmulatedRunScoresWithinTenPercentOfAnInProcessRunWithNoUnderrun) {
  const auto state = test::state_dir("run");
  const ToolRun run =
      test::tnvctl(state, "--emu --json run " + gcode::test::test_piece_path("circle_chords_0p1mm.ngc"));
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  for (const char* key : {"contour_error_max_um", "contour_error_mean_um", "contour_error_std_um", "path_deviation_max_um",
                          "accel_ratio_max", "jerk_ratio_max", "feed_ratio", "cycle_time_s", "underruns"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["underruns"], 0);
  EXPECT_TRUE(j["telemetry_complete"].get<bool>());
  EXPECT_NE(run.err.find("run: line"), std::string::npos) << "progress on stderr";

  std::uint64_t underruns = 0;
  const hil::PathScore local = in_process_score("circle_chords_0p1mm.ngc", underruns);
  EXPECT_EQ(underruns, 0u);
  const double max_um = j["contour_error_max_um"].get<double>();
  const double mean_um = j["contour_error_mean_um"].get<double>();
  std::printf("[run] circle_chords_0p1mm.ngc: tnvctl --emu contour max %.4f mean %.4f std %.4f um, cycle %.3f s, "
              "feed ratio %.3f, accel %.3f, jerk %.3f; in-process max %.4f mean %.4f std %.4f um, cycle %.3f s, "
              "feed ratio %.3f, accel %.3f, jerk %.3f\n",
              max_um, mean_um, j["contour_error_std_um"].get<double>(), j["cycle_time_s"].get<double>(),
              j["feed_ratio"].get<double>(), j["accel_ratio_max"].get<double>(), j["jerk_ratio_max"].get<double>(),
              local.contour_error_max_um, local.contour_error_mean_um, local.contour_error_std_um, local.cycle_time_s,
              local.feed_ratio, local.accel_ratio_max, local.jerk_ratio_max);
  EXPECT_NEAR(max_um, local.contour_error_max_um, 0.10 * local.contour_error_max_um);
  EXPECT_NEAR(mean_um, local.contour_error_mean_um, 0.10 * local.contour_error_mean_um);
  EXPECT_NEAR(j["cycle_time_s"].get<double>(), local.cycle_time_s, 0.05 * local.cycle_time_s);
  EXPECT_LE(j["path_deviation_max_um"].get<double>(), 5.0 + 2e-3);
  std::filesystem::remove_all(state);
}

TEST(TnvctlRun, ABadProgramIsRefusedNamingLineAndColumnBeforeAnythingIsSent) {
  const auto state = test::state_dir("run_bad");
  const auto bad = test::write_file(state / "bad.ngc", "G21 G90\nG1 X1 F100\n  G95 G1 X2\n");
  // An interface that does not exist: reaching for the bus would fail with exit 1, not 2.
  ToolRun r = test::tnvctl(state, "--iface tnv_none0 run " + bad.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("line 3, column 3: unsupported G-code G95"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("nothing was sent"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
  const auto z = test::write_file(state / "z.ngc", "G21\nG91 G18 G2 X1 Z0 I0.5 K0\n");
  r = test::tnvctl(state, "--iface tnv_none0 run " + z.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("line 2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("zero feed rate"), std::string::npos) << r.err;
  // A tool the program asks for must be in the tool table given.
  const auto tool = test::write_file(state / "tool.ngc", "T3 M6\nG1 X1 F100\nM2\n");
  r = test::tnvctl(state, "--iface tnv_none0 run " + tool.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("requested tool 3 not found in the tool table"), std::string::npos) << r.err;
  r = test::tnvctl(state, "--iface tnv_none0 run " + (state / "missing.ngc").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("cannot open: No such file"), std::string::npos) << r.err;
  // A FIFO is refused at once, not read until a writer comes.
  const std::string fifo = (state / "fifo.ngc").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  r = test::tnvctl(state, "--iface tnv_none0 run " + fifo);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("not a regular file"), std::string::npos) << r.err;
  std::filesystem::remove_all(state);
}

// A run from line after a tool change, without a terminal: the check before
// sending starts from the tool the run starts with. A fresh emulated node
// knows none (the start changes to T2: refused, naming why and the option);
// with --tool-in-spindle 2 there is no change and it runs.
// (ProgramFromLine.TheToolInTheSpindleIsTheNodesWhenItKnowsIt: the node's own answer.)
TEST(TnvctlRun, ARunFromLineChecksItsPausesWithTheToolInTheSpindle) {
  const auto state = test::state_dir("run_from_line_tool");
  const auto tbl = test::write_file(state / "tools.tbl", "T2 P2 Z0 D6\n");
  const auto prog = test::write_file(state / "part.ngc", "G21 G91 F600\nT2 M6\nG1 X3\nG1 Y3\nM2\n");
  const std::string run = "--emu --json run " + prog.string() + " --no-score --tool-table " + tbl.string() +
                          " --from-line 4";
  ToolRun r = test::tnvctl(state, run + " </dev/null");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("the program pauses (line 4: tool change (M6))"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the node reports no tool in the spindle"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--tool-in-spindle T says tool T is in"), std::string::npos) << r.err;
  r = test::tnvctl(state, run + " --tool-in-spindle 2 </dev/null");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["pauses"].empty()) << j.dump();
  std::filesystem::remove_all(state);
}

// The dialect on the emulated node: a work offset from --var-file, a tool
// from --tool-table (its M6 pauses: refused without a terminal unless
// --resume-after-s is given), a subroutine in a file beside the program,
// the spindle sent, coolant counted and not sent; the report has lines,
// segments, tool changes, the pause and the programmed cycle time.
TEST(TnvctlRun, ToolTableVarFileAndSubroutinesWithTheirReport) {
  const auto state = test::state_dir("run_dialect");
  const auto tbl = test::write_file(state / "tools.tbl", "T2 P2 Z30 D6\n");
  const auto var = test::write_file(state / "offsets.var", "5221 2\n5222 1\n");
  test::write_file(state / "side.ngc", "o<side> sub\n  G91 G1 X#1 F600\n  G90\no<side> endsub\nM2\n");
  const auto prog = test::write_file(state / "part.ngc",
                                     "T2 M6\nM3 S1000 M8\nG0 X0 Y0\no<side> call [3]\nG4 P0.2\nG0 X0\nM2\n");
  // The M6 pauses: without a terminal to press Enter on, the run needs --resume-after-s.
  ToolRun r = test::tnvctl(state, "--iface tnv_none0 run " + prog.string() + " --tool-table " + tbl.string() +
                                      " --var-file " + var.string() + " </dev/null");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("the program pauses (line 1: tool change (M6)), and stdin is not a terminal"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("nothing was sent"), std::string::npos) << r.err;
  r = test::tnvctl(state, "--emu --json run " + prog.string() + " --no-score --tool-table " + tbl.string() +
                              " --var-file " + var.string() + " --resume-after-s 0.2 </dev/null");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.err.find("paused at line 1: tool change (M6), tool 2: continuing in 0.2 s"), std::string::npos) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["pauses"].size(), 1u) << j.dump();
  EXPECT_EQ(j["pauses"][0]["line"], 1);
  EXPECT_EQ(j["pauses"][0]["tool"], 2);
  EXPECT_GE(j["paused_s"].get<double>(), 0.2);
  EXPECT_EQ(j["tool_changes"], 1);
  EXPECT_EQ(j["spindle_starts"], 1);
  EXPECT_EQ(j["spindle_commands"], 3) << "M6's stop, M3 S1000, M2's stop";
  EXPECT_EQ(j["coolant_starts_not_sent"], 1);
  EXPECT_EQ(j["lines_run"], 7 + 3) << "the program's seven lines, and the subroutine's two lines and endsub once";
  // M6's spindle stop and pause, M3 S1000, to G54's X2 Y1 (unless the table stands there), 3 mm at 10 mm/s,
  // the dwell, 3 mm back at the rapid feed, M2's spindle stop.
  const int segments = j["segments"].get<int>();
  EXPECT_TRUE(segments == 7 || segments == 8) << segments;
  const double tail_s = 3.0 / 10.0 + 0.2 + 3.0 / 50.0;
  EXPECT_GE(j["programmed_time_s"].get<double>(), tail_s - 1e-9);
  EXPECT_EQ(j["elements_accepted"].get<int>(), segments);
  // Without the tool table T2 is not known: refused before anything is sent.
  r = test::tnvctl(state, "--iface tnv_none0 run " + prog.string() + " --var-file " + var.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("requested tool 2 not found"), std::string::npos) << r.err;
  std::filesystem::remove_all(state);
}

TEST(TnvctlRun, CtrlCStopsOnThePathAndExitsOne) {
  const auto state = test::state_dir("run_int");
  const std::string err_path = (state / "err.txt").string();
  const std::string cmd = "XDG_STATE_HOME=" + state.string() + " exec " + TNVCTL_EXE + " --emu run " +
                          gcode::test::test_piece_path("nas979_diamond_circle_square.ngc") + " 2>" + err_path +
                          " >/dev/null";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto read_err = [&] {
    std::ifstream in(err_path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  // Wait for the first progress line (the program runs), then Ctrl-C.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (read_err().find("run: line") == std::string::npos && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ::kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "tnvctl died of the signal instead of stopping the program";
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const std::string err = read_err();
  EXPECT_NE(err.find("stopped by Ctrl-C at line"), std::string::npos) << err;
  EXPECT_NE(err.find("controlled stop on the path"), std::string::npos) << err;
  std::filesystem::remove_all(state);
}

// The run-from-line options are shared with `tnvctl gcode canon` (no device needed there).
TEST(TnvctlRun, GcodeCanonRunsFromALineWithTheSharedOptions) {
  const auto state = test::state_dir("canon_from");
  const auto prog = test::write_file(state / "p.ngc", "G21 G90\nG1 X1 F100\nG1 X2\nM2\n");
  const ToolRun r = test::tnvctl(state, "gcode canon " + prog.string() +
                                            " --from-line 3 --machine-position 5 0 0 --approach-height 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("COMMENT(\"interpreter: run from line 3\")"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000"), std::string::npos) << "the approach to line 3's start: "
                                                                                        << r.out;
  const ToolRun bad = test::tnvctl(state, "gcode canon " + prog.string() + " --from-pass 2");
  EXPECT_EQ(bad.exit_code, 2);
  std::filesystem::remove_all(state);
}

TEST(TnvctlRun, HelpReadsLikeAManualPage) {
  const ToolRun r = test::run_tool(std::string(TNVCTL_EXE) + " run --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* section : {"G-CODE", "PAUSES", "FEED HOLD", "--hold-at", "--resume-at", "SIGUSR1", "RUN FROM LINE",
                              "--from-line", "--resume-after-s", "--optional-stop",
                              "PROGRESS", "CTRL-C", "SCORE", "EXIT CODES", "EXAMPLES", "--feed-override",
                              "--tool-table", "--var-file", "--subroutine-path"})
    EXPECT_NE(r.out.find(section), std::string::npos) << section;
}

}  // namespace
}  // namespace tnv
