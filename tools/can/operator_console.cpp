#include "tools/can/operator_console.hpp"

#include <poll.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <iterator>

namespace tnv::can_host {

namespace {

// 0 nothing new, 1 hold asked (SIGUSR1), 2 resume asked (SIGUSR2).
std::atomic<int> g_signal_request{0};
extern "C" void on_hold_signal(int) { g_signal_request = 1; }
extern "C" void on_resume_signal(int) { g_signal_request = 2; }

struct sigaction g_saved_usr1 {};
struct sigaction g_saved_usr2 {};

void catch_signal(int sig, void (*handler)(int), struct sigaction& saved) {
  struct sigaction sa {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(sig, &sa, &saved);
}

// A signal that ends the process (kill, a closed terminal, Ctrl-\) must not
// leave the terminal without echo: its handler gives the modes back, then
// the process dies of the signal as it would have. Ctrl-C is the run's own
// (it stops the program, and the console's destructor gives them back).
constexpr int kEndingSignals[] = {SIGTERM, SIGHUP, SIGQUIT};
struct sigaction g_saved_ending[std::size(kEndingSignals)] {};
bool g_caught_ending[std::size(kEndingSignals)] {};
termios g_terminal_modes{};                // what the terminal had before the console
volatile std::sig_atomic_t g_terminal_fd = -1;  // >= 0 while the console has changed them

// The terminal's modes back, then `sig` raised with its default action (it
// takes effect once the handler that called this unblocks it). Only
// async-signal-safe calls (tcsetattr, sigaction, raise).
void give_back_modes_and_raise_by_default(int sig) {
  if (g_terminal_fd >= 0) tcsetattr(g_terminal_fd, TCSANOW, &g_terminal_modes);
  struct sigaction by_default {};
  by_default.sa_handler = SIG_DFL;
  sigemptyset(&by_default.sa_mask);
  sigaction(sig, &by_default, nullptr);
  raise(sig);
}

extern "C" void on_ending_signal(int sig) {
  // The signal is blocked in here: raised again, it ends the process once this returns.
  give_back_modes_and_raise_by_default(sig);
}

// Ctrl-Z (SIGTSTP) stops the process as a shell's job control expects, with
// the terminal as it was before the console (the shell gets its echo back);
// once continued (SIGCONT) the console takes its modes again. The stop
// itself is the default action, raised from the handler.
termios g_console_modes{};  // what the console sets: keys one by one, no echo
bool g_caught_stop = false;
struct sigaction g_saved_stop {};

extern "C" void on_console_stop(int) {
  // Only async-signal-safe calls. SIGTSTP is blocked in here: raised with
  // the default action, it stops the process when it is unblocked, and the
  // calls after that run only once the process is continued. In an orphaned
  // process group the kernel drops it (nobody would continue the process):
  // then the modes are simply taken again.
  const int saved_errno = errno;
  const bool had = g_terminal_fd >= 0;
  give_back_modes_and_raise_by_default(SIGTSTP);
  sigset_t stop{};
  sigemptyset(&stop);
  sigaddset(&stop, SIGTSTP);
  sigprocmask(SIG_UNBLOCK, &stop, nullptr);  // stopped here until SIGCONT
  sigprocmask(SIG_BLOCK, &stop, nullptr);    // another Ctrl-Z waits for this handler's end
  struct sigaction replaced {};  // the default just set: g_saved_stop keeps what was there before the console
  catch_signal(SIGTSTP, on_console_stop, replaced);
  // Continued in the background (`bg`), this tcsetattr stops the process by
  // SIGTTOU until it is in the foreground again: the shell keeps its modes.
  if (had && g_terminal_fd >= 0) tcsetattr(g_terminal_fd, TCSANOW, &g_console_modes);
  errno = saved_errno;
}

// Only where the signal has its default action: one ignored (nohup, or a
// shell without job control for SIGTSTP) or handled by someone else is left
// as it is.
bool has_default_action(int sig) {
  struct sigaction now {};
  return sigaction(sig, nullptr, &now) == 0 && now.sa_handler == SIG_DFL && (now.sa_flags & SA_SIGINFO) == 0;
}

void catch_console_signals() {
  for (std::size_t i = 0; i < std::size(kEndingSignals); ++i) {
    g_caught_ending[i] = has_default_action(kEndingSignals[i]);
    if (g_caught_ending[i]) catch_signal(kEndingSignals[i], on_ending_signal, g_saved_ending[i]);
  }
  g_caught_stop = has_default_action(SIGTSTP);
  if (g_caught_stop) catch_signal(SIGTSTP, on_console_stop, g_saved_stop);
}

void release_console_signals() {
  if (g_caught_stop) sigaction(SIGTSTP, &g_saved_stop, nullptr);
  for (std::size_t i = 0; i < std::size(kEndingSignals); ++i)
    if (g_caught_ending[i]) sigaction(kEndingSignals[i], &g_saved_ending[i], nullptr);
}

}  // namespace

OperatorConsole::OperatorConsole(int fd, std::vector<gcode::FeedHoldWindow> schedule, std::function<double()> clock_s)
    : fd_(fd), terminal_(isatty(fd) != 0), schedule_(std::move(schedule)), clock_s_(std::move(clock_s)) {
  if (terminal_) {
    termios t{};
    if (tcgetattr(fd_, &t) == 0) {
      saved_ = t;
      g_terminal_modes = t;
      t.c_lflag &= static_cast<tcflag_t>(~(ICANON | ECHO));
      t.c_cc[VMIN] = 0;
      t.c_cc[VTIME] = 0;
      g_console_modes = t;
      std::atomic_signal_fence(std::memory_order_seq_cst);  // the modes are in place before a handler may read them
      g_terminal_fd = fd_;
      catch_console_signals();
      tcsetattr(fd_, TCSANOW, &t);
    }
  }
  g_signal_request = 0;
  catch_signal(SIGUSR1, on_hold_signal, g_saved_usr1);
  catch_signal(SIGUSR2, on_resume_signal, g_saved_usr2);
}

OperatorConsole::~OperatorConsole() {
  sigaction(SIGUSR1, &g_saved_usr1, nullptr);
  sigaction(SIGUSR2, &g_saved_usr2, nullptr);
  if (saved_) {
    tcsetattr(fd_, TCSANOW, &*saved_);
    g_terminal_fd = -1;
    release_console_signals();  // after the modes are back: a signal before this finds them given back already
  }
}

void OperatorConsole::read_keys() {
  for (;;) {
    pollfd p{fd_, POLLIN, 0};
    if (poll(&p, 1, 0) <= 0 || (p.revents & POLLIN) == 0) return;
    char buf[64];
    const ssize_t n = read(fd_, buf, sizeof buf);
    if (n <= 0) return;  // end of input: no more keys
    for (ssize_t i = 0; i < n; ++i) {
      if (buf[i] == '\n' || buf[i] == '\r') enters_ += hold_ ? 0 : 1;  // typed while held: dropped
      else if (buf[i] == ' ' && terminal_) set_hold(!hold_);  // a space in a piped file is no key
    }
  }
}

void OperatorConsole::set_hold(bool on) {
  if (on == hold_) return;
  hold_ = on;
  ++hold_changes_;
}

bool OperatorConsole::take_enter() {
  read_keys();
  // A pause cannot be continued while the feed is held (the node refuses it): an Enter then is dropped.
  if (hold_) enters_ = 0;
  if (enters_ == 0) return false;
  enters_ = 0;
  return true;
}

void OperatorConsole::forget_enter() {
  if (terminal_) tcflush(fd_, TCIFLUSH);
  read_keys();
  enters_ = 0;
}

bool OperatorConsole::hold_wanted() {
  read_keys();
  if (const int request = g_signal_request.exchange(0); request != 0) set_hold(request == 1);
  if (schedule_.empty() || !clock_s_) return hold_;
  const double now_s = clock_s_();
  if (!started_s_) started_s_ = now_s;
  if (const bool scheduled = gcode::feed_held_at(schedule_, now_s - *started_s_); scheduled != scheduled_) {
    scheduled_ = scheduled;
    set_hold(scheduled);
  }
  return hold_;
}

}  // namespace tnv::can_host
