#pragma once
// Which browser tab may send commands and parameter changes. The server is
// one host on the bus (the node's ownership rules apply to it as to any
// host); between browsers, the tab that took control holds it until it
// gives it back or goes quiet (no request, no heartbeat) for `deadman`:
// a closed tab, a laptop asleep or a network gone loses control as a
// pendant's released enable switch does. Every other tab reads only.
#include <chrono>
#include <mutex>
#include <string>

namespace tnv::serve {

inline constexpr const char* kAnotherBrowserHasControl = "another browser has control";

class BrowserControl {
 public:
  using Clock = std::chrono::steady_clock;
  explicit BrowserControl(std::chrono::milliseconds deadman) : deadman_(deadman) {}

  // "" when `token` has control now, else why not (the token is malformed,
  // or another tab holds control). The holder taking it again is fine.
  std::string take(const std::string& token, Clock::time_point now);
  // Gives control back if `token` holds it; false otherwise.
  bool release(const std::string& token);
  // The tab is alive (its heartbeat); false when it does not hold control.
  bool seen(const std::string& token, Clock::time_point now);
  // The tab's telemetry stream closed (the tab was closed or reloaded): a
  // holder's control lapses at the next lapse().
  void gone(const std::string& token);
  // Ends a holder's control once it has been quiet for `deadman`: its
  // token (once), else "".
  std::string lapse(Clock::time_point now);
  // "" when `token` may send commands, else the refusal text.
  std::string check(const std::string& token, Clock::time_point now);
  bool holds(const std::string& token, Clock::time_point now);
  bool anyone_holds(Clock::time_point now);

  // A tab token: 8..64 characters of [A-Za-z0-9_-].
  static bool valid_token(const std::string& token);

 private:
  bool expired(Clock::time_point now) const;  // mutex held
  std::mutex mutex_;
  std::chrono::milliseconds deadman_;
  std::string holder_;  // "" = nobody
  Clock::time_point holder_seen_{};
  bool holder_gone_ = false;  // its telemetry stream closed
};

}  // namespace tnv::serve
