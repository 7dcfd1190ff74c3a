// `tnvctl run` and the operator: a feed hold by the space key on a
// terminal, on a schedule (--hold-at / --resume-at) and by signals (SIGUSR1
// holds, SIGUSR2 resumes) goes to the node as COMMAND feed_hold / feed_resume, and the run
// ends as the run without a hold ends, its time longer by the hold; a
// program with a tool change (or any pause) is refused without a terminal
// to confirm it from, naming the line, before anything is sent.
#include <gtest/gtest.h>
#include <pty.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <termios.h>
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
// Makes the calling process's group a shell's job on its terminal: the
// kernel drops a stop signal with the default action sent to an orphaned
// group (nobody would continue it), and the group of a pseudo-terminal's
// session leader is orphaned (its parent, the test, is in another session).
// A member whose parent is in another group of the same session, as a job's
// shell is, makes it a job: a keeper in a group of its own forks a child
// that joins this one. Both die with the process (PR_SET_PDEATHSIG). Called
// in a forked child: async-signal-safe calls only.
void become_a_job() {
  struct sigaction by_default {};
  by_default.sa_handler = SIG_DFL;
  sigemptyset(&by_default.sa_mask);
  for (const int sig : {SIGTSTP, SIGTTIN, SIGTTOU}) ::sigaction(sig, &by_default, nullptr);  // as a shell's job has them
  int ready[2];
  if (::pipe(ready) != 0) ::_exit(126);
  const pid_t group = ::getpgrp();
  const pid_t leader = ::getpid();
  if (::fork() == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != leader) ::_exit(0);
    ::setpgid(0, 0);
    const pid_t keeper = ::getpid();
    if (::fork() == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != keeper) ::_exit(0);
      ::setpgid(0, group);
      for (int fd = 0; fd <= 2; ++fd) ::close(fd);
      if (::write(ready[1], "k", 1) != 1) ::_exit(0);
      for (;;) ::pause();
    }
    for (int fd = 0; fd <= 2; ++fd) ::close(fd);
    for (;;) ::pause();
  }
  char joined = 0;
  if (::read(ready[0], &joined, 1) != 1) ::_exit(126);
  ::close(ready[0]);
  ::close(ready[1]);
}

struct BackgroundRun {
  std::string err_path, out_path;
  int terminal = -1;
  pid_t pid = -1;

  // `as_a_job`: on the terminal as a shell's job, which Ctrl-Z (SIGTSTP) stops;
  // `stop_ignored`: started with SIGTSTP ignored, as by a shell without job control.
  BackgroundRun(const std::filesystem::path& state, const std::string& program, bool on_terminal,
                bool as_a_job = false, bool stop_ignored = false)
      : err_path((state / "err.txt").string()), out_path((state / "out.json").string()) {
    const std::string cmd = "XDG_STATE_HOME=" + state.string() + " exec " + TNVCTL_EXE + " --emu --json run " +
                            program + " --no-score " + (on_terminal ? "" : "</dev/null ") + "2>" + err_path + " >" +
                            out_path;
    pid = on_terminal ? ::forkpty(&terminal, nullptr, nullptr, nullptr) : ::fork();
    if (pid == 0) {
      if (as_a_job) become_a_job();
      if (stop_ignored) ::signal(SIGTSTP, SIG_IGN);
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
// Sends `sig` to the run: it dies of it, as without the terminal, and the
// terminal has its echo and line mode back.
void expect_dies_of_and_gives_the_modes_back(const BackgroundRun& run, int sig) {
  ASSERT_EQ(::kill(run.pid, sig), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(run.pid, &status, 0), run.pid);
  ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status;
  EXPECT_EQ(WTERMSIG(status), sig) << "it dies of the signal, as without the terminal";
  termios after{};
  ASSERT_EQ(::tcgetattr(run.terminal, &after), 0);
  EXPECT_NE(after.c_lflag & ECHO, 0u) << "the terminal's echo was not given back";
  EXPECT_NE(after.c_lflag & ICANON, 0u) << "the terminal's line mode was not given back";
}

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
  expect_dies_of_and_gives_the_modes_back(run, sig);
  ::close(run.terminal);
  std::filesystem::remove_all(state);
}

INSTANTIATE_TEST_SUITE_P(TermAndHup, TnvctlRunEndingSignal, ::testing::Values(SIGTERM, SIGHUP),
                         [](const ::testing::TestParamInfo<int>& signal) {
                           return std::string(signal.param == SIGTERM ? "sigterm" : "sighup");
                         });

// The terminal's modes once `echo_on` is what they show, up to 10 s: a
// continued process takes them in its handler, after the continue is reported.
bool wait_for_echo(int terminal, bool echo_on) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  for (;;) {
    termios t{};
    if (::tcgetattr(terminal, &t) == 0 && ((t.c_lflag & ECHO) != 0) == echo_on) return true;
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

// Ctrl-Z at a pause, as from a shell with job control: tnvctl stops with
// the terminal's echo and line mode given back (the shell is not left
// blind), takes its own modes again when continued (keys one by one, no
// echo; a second Ctrl-Z stops it again), reads its keys as before, and
// killed afterwards gives the modes back as ever.
TEST(TnvctlRunStop, CtrlZGivesTheShellItsEchoAndSigcontTakesTheConsoleModesAgain) {
  const auto state = test::state_dir("run_ctrl_z");
  const auto prog = test::write_file(state / "m0.ngc", "G21 G91\nG1 X2 F600\nM0\nG1 X-2\nM2\n");
  const BackgroundRun run(state, prog.string(), true, true);
  ASSERT_GE(run.pid, 0);
  ASSERT_TRUE(run.wait_for("press Enter to continue", 1)) << run.err();
  termios during{};
  ASSERT_EQ(::tcgetattr(run.terminal, &during), 0);
  ASSERT_EQ(during.c_lflag & ECHO, 0u) << "the keys are not echoed while the program runs";
  for (int round = 1; round <= 2; ++round) {
    ASSERT_EQ(::kill(run.pid, SIGTSTP), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(run.pid, &status, WUNTRACED), run.pid);
    ASSERT_TRUE(WIFSTOPPED(status)) << "round " << round << ": status " << status;
    EXPECT_EQ(WSTOPSIG(status), SIGTSTP);
    termios stopped{};
    ASSERT_EQ(::tcgetattr(run.terminal, &stopped), 0);
    EXPECT_NE(stopped.c_lflag & ECHO, 0u) << "round " << round << ": stopped with the terminal's echo off";
    EXPECT_NE(stopped.c_lflag & ICANON, 0u) << "round " << round << ": stopped with the terminal's line mode off";
    ASSERT_EQ(::kill(run.pid, SIGCONT), 0);
    ASSERT_EQ(::waitpid(run.pid, &status, WCONTINUED), run.pid);
    ASSERT_TRUE(WIFCONTINUED(status)) << "status " << status;
    EXPECT_TRUE(wait_for_echo(run.terminal, false)) << "round " << round << ": continued without its modes";
    termios again{};
    ASSERT_EQ(::tcgetattr(run.terminal, &again), 0);
    EXPECT_EQ(again.c_lflag & ICANON, 0u) << "round " << round << ": continued in line mode";
  }
  // Its keys after the continue: the space holds.
  ASSERT_EQ(::write(run.terminal, " ", 1), 1);
  EXPECT_TRUE(run.wait_for("holding", 1)) << run.err();
  int status = 0;
  EXPECT_EQ(::waitpid(run.pid, &status, WNOHANG), 0) << "the stops ended the run: " << run.err();
  expect_dies_of_and_gives_the_modes_back(run, SIGTERM);
  ::close(run.terminal);
  std::filesystem::remove_all(state);
}

// Where SIGTSTP would not stop tnvctl, it goes on with its modes: ignored
// (started so by a shell without job control, and kept so), or with the
// default action in an orphaned process group (the kernel drops the stop
// the console's handler raises, and the handler takes the modes again).
class TnvctlRunNoStop : public ::testing::TestWithParam<bool> {};

TEST_P(TnvctlRunNoStop, SigtstpThatCannotStopLeavesTheRunAndItsModesAsTheyWere) {
  const bool ignored = GetParam();
  const auto state = test::state_dir(std::string("run_no_stop_") + (ignored ? "ignored" : "orphaned"));
  const auto prog = test::write_file(state / "m0.ngc", "G21 G91\nG1 X2 F600\nM0\nG1 X-2\nM2\n");
  const BackgroundRun run(state, prog.string(), true, ignored, ignored);
  ASSERT_GE(run.pid, 0);
  ASSERT_TRUE(run.wait_for("press Enter to continue", 1)) << run.err();
  ASSERT_EQ(::kill(run.pid, SIGTSTP), 0);
  // A stopped run could not answer the space.
  ASSERT_EQ(::write(run.terminal, " ", 1), 1);
  EXPECT_TRUE(run.wait_for("holding", 1)) << run.err();
  int status = 0;
  ASSERT_EQ(::waitpid(run.pid, &status, WUNTRACED | WNOHANG), 0) << "status " << status;
  EXPECT_TRUE(wait_for_echo(run.terminal, false)) << "the run goes on with the terminal's echo on";
  expect_dies_of_and_gives_the_modes_back(run, SIGTERM);
  ::close(run.terminal);
  std::filesystem::remove_all(state);
}

INSTANTIATE_TEST_SUITE_P(IgnoredAndOrphaned, TnvctlRunNoStop, ::testing::Values(true, false),
                         [](const ::testing::TestParamInfo<bool>& ignored) {
                           return std::string(ignored.param ? "ignored" : "orphaned");
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
