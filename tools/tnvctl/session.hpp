#pragma once
// What every tnvctl command shares: the global options, the connection to
// the node (opened on first use: SocketCAN or the in-process emulated
// controller), the output (text or JSON) and the exit codes.
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "tools/can/node_client.hpp"
#include "tools/can_emu/emulated_bus.hpp"
#include "tools/can_emu/node_connection.hpp"

namespace tnv::tnvctl {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;   // refused by the node, timeout, device error, run failed
inline constexpr int kExitBadInput = 2;  // bad command line or input: nothing was sent

// Bad input found before anything was sent (exit 2).
class BadInput : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
// The node did what it was told but the outcome is a failure (a fault
// during a motion, an output file not written): exit 1.
class RunFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct GlobalOptions {
  std::string iface;  // SocketCAN interface, or unix:PATH (tnv-fw's Unix-socket CAN link)
  bool emu = false;   // the in-process emulated controller
  int node = 1;
  int host_id = 1;  // request tags, staged set and command ownership are this host's
  bool json = false;
  int timeout_ms = 250;
  std::string emu_scenario = "no-cut";
  int emu_seed = 0;
  std::string emu_storage;  // "" = default path
  std::string trace;        // "" = none; else every frame sent and received, candump -l format
};

// What a command reports: lines of text (printed at once, unless --json)
// and one JSON object (printed when the command ends, with --json).
class Report {
 public:
  explicit Report(bool json) : json_(json) {}
  void line(const std::string& text) const;
  bool json_mode() const noexcept { return json_; }
  // A command that streams JSON Lines or CSV on stdout (monitor) keeps
  // stdout pure: its summary (text lines, or the JSON object on one line)
  // goes to stderr.
  void summary_to_stderr() noexcept { summary_on_stderr_ = true; }
  bool summary_on_stderr() const noexcept { return summary_on_stderr_; }
  nlohmann::json data = nlohmann::json::object();

 private:
  bool json_;
  bool summary_on_stderr_ = false;
};

class Session {
 public:
  explicit Session(GlobalOptions options) : options_(std::move(options)) {}

  // Opens the connection on first use and checks the node's protocol
  // version. Throws BusError / RequestError / RunFailed.
  can_host::NodeClient& client();
  // The emulated controller, or nullptr on SocketCAN (opens the connection).
  can_host::EmulatedBus* emulated();
  bool is_emulated() const noexcept { return options_.emu; }
  // Gives back command ownership if this session took it (at the end of
  // tnvctl); a failure is reported on stderr, never thrown.
  void end() noexcept;
  // The emulated node, if this session opened one (never opens it).
  can_host::EmulatedBus* opened_emulation() const noexcept { return connection_ ? connection_->emulated() : nullptr; }
  const GlobalOptions& options() const noexcept { return options_; }
  // Set in script mode: JSON objects are printed one per line.
  bool compact_json = false;

 private:
  void open();
  GlobalOptions options_;
  std::unique_ptr<can_host::NodeConnection> connection_;
};

}  // namespace tnv::tnvctl
