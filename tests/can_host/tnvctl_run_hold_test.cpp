// `tnvctl run` and the operator: a feed hold by the space key on a
// terminal, on a schedule (--hold-at / --resume-at) and by signals (SIGUSR1
// holds, SIGUSR2 resumes) goes to the node as COMMAND feed_hold / feed_resume, and the run
// ends as the run without a hold ends, its time longer by the hold; a
// program with a tool change (or any pause) is refused without a terminal
// to confirm it from, naming the line, before anything is sent.
#include <gtest/gtest.h>
#include <pty.h>
#include <signal.h>
#include <termios.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <thread>

#include "tests/can_host/tnvctl_runner.hpp"
#include "tests/tools/gcode/test_piece_path.hpp"

namespace tnv {
namespace {

using test::ToolRun;

constexpr const char* kProgram = "G21 G91\nG1 X20 F1200\nG1 Y5\nG1 X-20\nM2\n";

// `tnvctl --emu --json run PROGRAM --no-score` started in the background,
// its stdin a pseudo-terminal (`on_terminal`) or /dev/null, its stderr and
// JSON to files: the tests wait for what it reports, never for a time.
struct BackgroundRun {
  std::string err_path, out_path;
  int terminal = -1;
  pid_t pid = -1;

  BackgroundRun(const std::filesystem::path& state, const std::string& program, bool on_terminal)
      : err_path((state / "err.txt").string()), out_path((state / "out.json").string()) {
    const std::string cmd = "XDG_STATE_HOME=" + state.string() + " exec " + TNVCTL_EXE + " --emu --json run " +
                            program + " --no-score " + (on_terminal ? "" : "</dev/null ") + "2>" + err_path + " >" +
                            out_path;
    pid = on_terminal ? ::forkpty(&terminal, nullptr, nullptr, nullptr) : ::fork();
    if (pid == 0) {
      ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
  }
  std::string err() const { return test::read_file(err_path); }
  // How often `text` stands in what the run reported.
  int count(const std::string& text) const {
    const std::string e = err();
    int n = 0;
    for (std::size_t at = e.find(text); at != std::string::npos; at = e.find(text, at + 1)) ++n;
    return n;
  }
  // Until `text` stands there `n` times, up to 120 s.
  bool wait_for(const std::string& text, int n = 1) const {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (count(text) < n && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    return count(text) >= n;
  }
};

TEST(TnvctlRunHold, AScheduledHoldWaitsOnThePathAndTheRunEndsAsWithoutIt) {
  const auto state = test::state_dir("run_hold_schedule");
  const auto prog = test::write_file(state / "p.ngc", kProgram);
  const ToolRun plain = test::tnvctl(state, "--emu --json run " + prog.string() + " </dev/null");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const ToolRun held = test::tnvctl(state, "--emu --json run " + prog.string() +
                                                " --hold-at 0.3 --resume-at 0.8 --hold-at 1.2 --resume-at 1.5 </dev/null");
  ASSERT_EQ(held.exit_code, 0) << held.err;
  const nlohmann::json p = nlohmann::json::parse(plain.out);
  const nlohmann::json h = nlohmann::json::parse(held.out);
  EXPECT_EQ(p["held_s"].get<double>(), 0.0);
  EXPECT_EQ(h["feed_hold_changes"], 4) << "two holds, two resumes";
  // Bus time between the stream's looks (a PROGRAM_STATUS round every few ms).
  EXPECT_NEAR(h["held_s"].get<double>(), 0.8, 0.05);
  EXPECT_EQ(h["elements_accepted"], p["elements_accepted"]) << "nothing lost";
  EXPECT_GE(h["run_s"].get<double>(), p["run_s"].get<double>() + 0.8 - 0.05);
  // The same geometry: within the planner's 5 um path tolerance plus 1 um of following, as without the holds
  // (measured 5.0 um against 3.75 um: a hold near the corner rests on the corner's blend and restarts from it).
  EXPECT_LE(h["contour_error_max_um"].get<double>(), 6.0) << "the holds cost the contour";
  EXPECT_LE(p["contour_error_max_um"].get<double>(), 6.0);
  EXPECT_LE(h["path_deviation_max_um"].get<double>(), 5.0 + 1e-6) << "braked off the path";
  EXPECT_NE(held.err.find("holding"), std::string::npos) << "the node reported holding: " << held.err;
  // Bad pairs are refused before anything is sent.
  const ToolRun bad = test::tnvctl(state, "--iface tnv_none0 run " + prog.string() + " --hold-at 2 --resume-at 1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--resume-at 1 must come after its --hold-at 2"), std::string::npos) << bad.err;
  std::filesystem::remove_all(state);
}

TEST(TnvctlRunHold, SigusrOneHoldsAndSigusrTwoResumesWithoutATerminal) {
  const auto state = test::state_dir("run_hold_signal");
  const BackgroundRun run(state, gcode::test::test_piece_path("nas979_diamond_circle_square.ngc"), false);
  ASSERT_GE(run.pid, 0);
  ASSERT_TRUE(run.wait_for("run: line")) << run.err();
  ::kill(run.pid, SIGUSR1);
  EXPECT_TRUE(run.wait_for("holding")) << run.err();
  ::kill(run.pid, SIGUSR2);
  int status = 0;
  ASSERT_EQ(::waitpid(run.pid, &status, 0), run.pid);
  ASSERT_TRUE(WIFEXITED(status)) << "tnvctl died of the signal instead of holding";
  EXPECT_EQ(WEXITSTATUS(status), 0) << run.err();
  const nlohmann::json j = nlohmann::json::parse(test::read_file(run.out_path));
  EXPECT_EQ(j["feed_hold_changes"], 2);
  EXPECT_GT(j["held_s"].get<double>(), 0.0);
  EXPECT_EQ(j["elements_accepted"], j["elements"]) << "the whole program ran after the resume";
  std::filesystem::remove_all(state);
}

// On a terminal (a pseudo-terminal here) the space key holds and the next
// space resumes: the terminal gives tnvctl each key as typed, and gets its
// line mode back at the end.
TEST(TnvctlRunHold, TheSpaceKeyOnATerminalHoldsAndTheNextSpaceResumes) {
  const auto state = test::state_dir("run_hold_key");
  const BackgroundRun run(state, gcode::test::test_piece_path("nas979_diamond_circle_square.ngc"), true);
  ASSERT_GE(run.pid, 0);
  ASSERT_TRUE(run.wait_for("run: line")) << run.err();
  termios during{};
  ASSERT_EQ(::tcgetattr(run.terminal, &during), 0);
  EXPECT_EQ(during.c_lflag & ICANON, 0u) << "keys wait for Enter while the program runs";
  ASSERT_EQ(::write(run.terminal, " ", 1), 1);
  EXPECT_TRUE(run.wait_for("holding")) << run.err();
  ASSERT_EQ(::write(run.terminal, " ", 1), 1);
  int status = 0;
  ASSERT_EQ(::waitpid(run.pid, &status, 0), run.pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << run.err();
  termios after{};
  ASSERT_EQ(::tcgetattr(run.terminal, &after), 0);
  EXPECT_NE(after.c_lflag & ICANON, 0u) << "the terminal's line mode was not given back";
  ::close(run.terminal);
  const nlohmann::json j = nlohmann::json::parse(test::read_file(run.out_path));
  EXPECT_EQ(j["feed_hold_changes"], 2);
  EXPECT_GT(j["held_s"].get<double>(), 0.0);
  EXPECT_EQ(j["elements_accepted"], j["elements"]) << "the whole program ran after the resume";
  std::filesystem::remove_all(state);
}

// A hold while paused: an Enter typed while held is dropped (the node would
// refuse to continue a held pause and the run would end failed); after the
// resume the pause waits for an Enter of its own.
TEST(TnvctlRunHold, AnEnterWhileHeldAtAPauseIsDroppedAndTheNextContinues) {
  const auto state = test::state_dir("run_hold_pause_key");
  const auto prog = test::write_file(state / "m0.ngc", "G21 G91\nG1 X2 F600\nM0\nG1 X-2\nM2\n");
  const BackgroundRun run(state, prog.string(), true);
  ASSERT_GE(run.pid, 0);
  ASSERT_TRUE(run.wait_for("press Enter to continue", 1)) << run.err();
  ASSERT_EQ(::write(run.terminal, " ", 1), 1);
  ASSERT_TRUE(run.wait_for("holding", 1)) << run.err();
  const int paused_lines = run.count(" paused");
  ASSERT_EQ(::write(run.terminal, "\n ", 2), 2);  // Enter while held, then resume
  ASSERT_TRUE(run.wait_for(" paused", paused_lines + 1)) << "the node back at the pause: " << run.err();
  // Were the Enter taken, the pause would go on at once (the rest is 0.2 s of emulated time).
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  int status = 0;
  EXPECT_EQ(::waitpid(run.pid, &status, WNOHANG), 0) << "the Enter typed while held continued the pause: "
                                                  << run.err();
  ASSERT_EQ(::write(run.terminal, "\n", 1), 1);
  ASSERT_EQ(::waitpid(run.pid, &status, 0), run.pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << run.err();
  ::close(run.terminal);
  const nlohmann::json j = nlohmann::json::parse(test::read_file(run.out_path));
  EXPECT_EQ(j["feed_hold_changes"], 2);
  EXPECT_EQ(j["pauses"].size(), 1u);
  EXPECT_EQ(j["elements_accepted"], j["elements"]);
  std::filesystem::remove_all(state);
}

// Killed while it waits at a pause (SIGTERM, or SIGHUP as when its
// terminal goes away), tnvctl still dies of the signal, and the terminal
// has its echo and line mode back: the operator's shell is not left blind.
class TnvctlRunEndingSignal : public ::testing::TestWithParam<int> {};

TEST_P(TnvctlRunEndingSignal, GivesTheTerminalItsEchoBackAndDiesOfIt) {
  const int sig = GetParam();
  const auto state = test::state_dir(std::string("run_ending_signal_") + std::to_string(sig));
  const auto prog = test::write_file(state / "m0.ngc", "G21 G91\nG1 X2 F600\nM0\nG1 X-2\nM2\n");
  const BackgroundRun run(state, prog.string(), true);
  ASSERT_GE(run.pid, 0);
  ASSERT_TRUE(run.wait_for("press Enter to continue", 1)) << run.err();
  termios during{};
  ASSERT_EQ(::tcgetattr(run.terminal, &during), 0);
  ASSERT_EQ(during.c_lflag & ECHO, 0u) << "the keys are not echoed while the program runs";
  ASSERT_EQ(::kill(run.pid, sig), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(run.pid, &status, 0), run.pid);
  ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status;
  EXPECT_EQ(WTERMSIG(status), sig) << "it dies of the signal, as without the terminal";
  termios after{};
  ASSERT_EQ(::tcgetattr(run.terminal, &after), 0);
  EXPECT_NE(after.c_lflag & ECHO, 0u) << "the terminal's echo was not given back";
  EXPECT_NE(after.c_lflag & ICANON, 0u) << "the terminal's line mode was not given back";
  ::close(run.terminal);
  std::filesystem::remove_all(state);
}

INSTANTIATE_TEST_SUITE_P(TermAndHup, TnvctlRunEndingSignal, ::testing::Values(SIGTERM, SIGHUP),
                         [](const ::testing::TestParamInfo<int>& signal) {
                           return std::string(signal.param == SIGTERM ? "sigterm" : "sighup");
                         });

// Without a terminal a tool change could never be confirmed: refused before
// anything is sent, naming the first pause and the first M6 with their lines.
TEST(TnvctlRunHold, AToolChangeWithoutATerminalIsRefusedNamingItsLineBeforeAnythingIsSent) {
  const auto state = test::state_dir("run_m6_no_tty");
  const auto tbl = test::write_file(state / "tools.tbl", "T2 P2 Z30 D6\n");
  const auto only_m6 = test::write_file(state / "m6.ngc", "G21 G91\nG1 X1 F600\nT2 M6\nG1 X1\nM2\n");
  // tnv_none0 does not exist: a refusal that opened the bus would fail there instead.
  ToolRun r = test::tnvctl(state, "--iface tnv_none0 run " + only_m6.string() + " --tool-table " + tbl.string() +
                                      " </dev/null");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("the program pauses (line 3: tool change (M6))"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("nothing was sent"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--resume-after-s"), std::string::npos) << "names the way to run it unattended: " << r.err;
  const auto m0_then_m6 = test::write_file(state / "m0m6.ngc", "G21 G91\nM0\nG1 X1 F600\nT2 M6\nG1 X1\nM2\n");
  r = test::tnvctl(state, "--iface tnv_none0 run " + m0_then_m6.string() + " --tool-table " + tbl.string() +
                              " </dev/null");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("the program pauses (line 2: program stop (M0)); its first tool change (M6, tool 2) is at line 4"),
            std::string::npos)
      << r.err;
  std::filesystem::remove_all(state);
}

}  // namespace
}  // namespace tnv
