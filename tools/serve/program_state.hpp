#pragma once
// The page's program run, as the HTTP handlers and the telemetry stream see
// it while the node thread streams it: idle, starting (planned and
// checked), running (its elements going out), then ended (done,
// interrupted, failed or refused) with the last line the node ran. Stop,
// E-stop, the dead-man rule and a release set the interrupt flag here
// directly: the program's job holds the node thread, so a stop job queued
// behind it would wait for the program's end.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

#include "tools/can/program_stream.hpp"

namespace tnv::serve {

class ProgramState {
 public:
  // A new run: false (and nothing changed) while one is starting or running.
  bool begin(const nlohmann::json& summary);
  // The run's elements start going out (the handler answers now).
  void streaming();
  void progress(const can_host::StreamProgress& p);
  // end: "done", "interrupted", "failed" or "refused".
  void finish(const std::string& end, const std::string& message);
  // Stops the run on its path at the stream's next look: true when one was starting or running.
  // `estop`: the node thread sends the e-stop at that look, before the stream brakes and ends.
  bool interrupt(bool estop = false);
  bool interrupted() const noexcept { return interrupt_.load(); }
  bool estop_requested() const noexcept { return estop_.load(); }
  // The node rests at a program pause (M0, M1, M6); progress() past it clears it.
  void paused(const can_host::StreamPause& pause);
  // The Resume button (the tab with control): false when the program does not rest at a pause.
  bool resume();
  // The stream's look while paused: true once after resume().
  bool take_resume() noexcept { return resume_.exchange(false); }
  // The Feed hold button (the tab with control): false (nothing changed) when no program is running.
  bool feed_hold(bool on);
  bool feed_hold_wanted() const noexcept { return hold_.load(); }
  bool active() const;
  bool is_streaming() const;  // its elements are going out now
  // {"phase", "run", "line", "element", "total", "fraction", "underruns", "end", "message",
  //  "program" (its summary), "interrupting" (a stop was asked),
  //  "pause": null or {"line", "reason", "tool", "text"} while it rests at a pause,
  //  "spindle_tool": null (not reported) or {"known", "tool", "text"}: the node's PROGRAM_TOOL,
  //  "feed_hold": the operator's hold asked for, "node_state": PROGRAM_STATUS.state (holding once it holds)}
  nlohmann::json json() const;

 private:
  mutable std::mutex mutex_;
  std::atomic<bool> interrupt_{false};
  std::atomic<bool> estop_{false};
  std::atomic<bool> resume_{false};
  std::atomic<bool> hold_{false};  // the operator's feed hold, sent by the run's stream
  std::string node_state_ = "none";  // PROGRAM_STATUS.state as the run last saw it
  nlohmann::json pause_;  // null unless paused
  nlohmann::json spindle_tool_;  // the node's last PROGRAM_TOOL seen by a run, null before any
  std::string phase_ = "idle";  // idle | starting | running | ended
  std::uint64_t run_ = 0;       // the page tells one run's end from the next's
  nlohmann::json summary_;
  int line_ = 0;
  std::size_t element_ = 0;
  std::size_t total_ = 0;
  double fraction_ = 0.0;
  std::uint64_t underruns_ = 0;
  std::string end_;
  std::string message_;
};

}  // namespace tnv::serve
