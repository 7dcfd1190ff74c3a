#pragma once
// The operator of a program run from a console (`tnvctl run`): Enter
// continues a program pause; the feed hold switch is flipped by the space
// key on a terminal, set by SIGUSR1 and cleared by SIGUSR2 (a run without a
// terminal: `kill -USR1 PID`), and follows a --hold-at / --resume-at
// schedule. The switch is what StreamOptions::feed_hold asks (the node's
// COMMAND feed_hold / feed_resume, as the page's button sends them).
#include <functional>
#include <optional>
#include <vector>

#include <termios.h>

#include "tools/gcode/feed_hold_schedule.hpp"

namespace tnv::can_host {

class OperatorConsole {
 public:
  // fd is read for keys; on a terminal it delivers keys one by one, without
  // echo, while this lives (Ctrl-C still signals), and SIGTERM, SIGHUP and
  // SIGQUIT give the terminal its modes back before they end the process;
  // Ctrl-Z (SIGTSTP) gives them back for the stop and takes them again at SIGCONT.
  // SIGUSR1 / SIGUSR2 are caught while this lives. One at a time. The schedule runs on `clock_s`
  // (the bus's time: simulated on an emulated node), from its first look.
  OperatorConsole(int fd, std::vector<gcode::FeedHoldWindow> schedule = {}, std::function<double()> clock_s = {});
  ~OperatorConsole();
  OperatorConsole(const OperatorConsole&) = delete;
  OperatorConsole& operator=(const OperatorConsole&) = delete;

  bool terminal() const noexcept { return terminal_; }
  // An Enter typed since the last call or forget_enter() (reads what is there, never waits); one typed
  // while the feed is held is dropped (resume first: the node does not continue a pause while held).
  bool take_enter();
  // Drops what was typed (an Enter before a pause is not an answer to it).
  void forget_enter();
  // The feed hold switch now: keys, signals and the schedule (its clock starts at the first call,
  // which the stream makes once the program runs). The last change of any of them wins.
  bool hold_wanted();
  int hold_changes() const noexcept { return hold_changes_; }

 private:
  void read_keys();
  void set_hold(bool on);

  int fd_;
  bool terminal_ = false;
  std::optional<termios> saved_;
  std::vector<gcode::FeedHoldWindow> schedule_;
  std::function<double()> clock_s_;
  std::optional<double> started_s_;
  bool scheduled_ = false;  // the schedule's switch at the last look
  bool hold_ = false;
  int enters_ = 0;
  int hold_changes_ = 0;
};

}  // namespace tnv::can_host
