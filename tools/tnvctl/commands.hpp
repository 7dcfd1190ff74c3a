#pragma once
// Each tnvctl command family registers its subcommands here (one file per
// family, like tools/tnv-hil). A subcommand's parse callback fills the
// action slot; the caller runs it on a Session: main() for one command,
// `script` for many on one session.
#include <CLI/CLI.hpp>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tools/can/node_identity.hpp"
#include "tools/can/telemetry_json.hpp"
#include "tools/tnvctl/session.hpp"

namespace tnv::tnvctl {

struct Action {
  Action(std::string name_, bool needs_device_, std::function<int(Session&, Report&)> run_,
         std::function<void()> check_ = {})
      : name(std::move(name_)), needs_device(needs_device_), run(std::move(run_)), check(std::move(check_)) {}
  std::string name;            // the command, for messages ("params set")
  bool needs_device = true;    // false: runs without --iface / --emu (dump-dbc, plot)
  std::function<int(Session&, Report&)> run;
  // Checks that need no node (names, ranges, files); throws BadInput. A
  // script runs every line's check before the first line is sent.
  std::function<void()> check;
};
using ActionSlot = std::optional<Action>;

void add_params_commands(CLI::App& app, ActionSlot& slot);   // params list | get | set | save | load | defaults
                                                             // | export | import
void add_motion_commands(CLI::App& app, ActionSlot& slot);   // circle, move, jog, stop, estop, enable, disable,
                                                             // clear-faults, zero, controller, status
void add_shaper_commands(CLI::App& app, ActionSlot& slot);   // shaper
void add_spindle_commands(CLI::App& app, ActionSlot& slot);  // spindle start | stop | speed
void add_monitor_commands(CLI::App& app, ActionSlot& slot);  // monitor
void add_capture_commands(CLI::App& app, ActionSlot& slot);  // capture
void add_tune_commands(CLI::App& app, ActionSlot& slot);     // identify, autotune
void add_freq_response_commands(CLI::App& app, ActionSlot& slot);  // freq-response
void add_output_commands(CLI::App& app, ActionSlot& slot);   // dump-dbc, plot
void add_commissioning_commands(CLI::App& app, ActionSlot& slot);  // commissioning enter | leave
void add_bore_commands(CLI::App& app, ActionSlot& slot);     // bore gauge | status | restart
void add_run_commands(CLI::App& app, ActionSlot& slot);      // run FILE.ngc
void add_gcode_commands(CLI::App& app, ActionSlot& slot);    // gcode canon FILE.ngc
void add_trace_commands(CLI::App& app, ActionSlot& slot);    // decode, replay
void add_script_commands(CLI::App& app, ActionSlot& slot);   // script
void add_serve_commands(CLI::App& app, ActionSlot& slot);    // serve (built with cpp-httplib)

// Every family above except `script` (what a script line may use).
void add_device_commands(CLI::App& app, ActionSlot& slot);

// One command line (without global options) parsed into an action, as a
// script line or `capture --run` does; nullopt with a one-line `error`.
std::optional<Action> parse_command_line(const std::vector<std::string>& args, std::string& error);

// Shell-like words of one line: blanks separate, '...' and "..." quote,
// backslash escapes, '#' starting a word comments out the rest; nullopt
// with `error` for an open quote.
std::optional<std::vector<std::string>> split_words(const std::string& line, std::string& error);

// Runs an action: exceptions become a message on stderr (and a JSON error
// object with --json) and the exit code.
int run_action(const Action& action, Session& session);

// `params set`: NAME=VALUE assignments staged and committed as one set (all
// or nothing), each change reported; throws BadInput / RequestError / RunFailed.
int set_params(const std::vector<std::string>& assignments, Session& session, Report& report);
// params export | import, under the `params` subcommand.
void add_param_file_commands(CLI::App& params, ActionSlot& slot);

// Shared helpers for the families.
std::uint8_t parse_axis(const std::string& name);  // "x" -> 0, "y" -> 1
// The --axis values of a command that also takes every axis at once: each
// axis' name, then `every` ({"x", "y", "all"}), and their help ("x, y or all").
std::vector<std::string> axis_values_or(const std::string& every);
std::string axis_help_or(const std::string& every);
const fw::can::ParamDef& param_named(const std::string& name);  // from the table, or throws BadInput
// Throws RunFailed when the node ended in a fault: names the reason.
void require_no_fault(const can_host::Heartbeat& hb, can_host::NodeClient& client, const std::string& what);
using can_host::heartbeat_json;  // tools/can/telemetry_json.hpp
// {"version": "0.1.0", "build_id": "1a2b3c4d", "protocol_version": 3}
nlohmann::json firmware_json(const can_host::NodeIdentity& id);
std::string heartbeat_text(const can_host::Heartbeat& hb);

}  // namespace tnv::tnvctl
