// Running actions (exit codes, error output) and parsing nested command
// lines (script lines, capture --run).
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "hal/axis_choice.hpp"
#include "tools/can/motion_run.hpp"
#include "tools/can/param_text.hpp"
#include "tools/cli/cli_frame.hpp"
#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

void add_device_commands(CLI::App& app, ActionSlot& slot) {
  add_params_commands(app, slot);
  add_motion_commands(app, slot);
  add_shaper_commands(app, slot);
  add_spindle_commands(app, slot);
  add_monitor_commands(app, slot);
  add_capture_commands(app, slot);
  add_tune_commands(app, slot);
  add_freq_response_commands(app, slot);
  add_output_commands(app, slot);
  add_commissioning_commands(app, slot);
  add_bore_commands(app, slot);
  add_run_commands(app, slot);
  add_gcode_commands(app, slot);
  add_trace_commands(app, slot);
}

std::optional<std::vector<std::string>> split_words(const std::string& line, std::string& error) {
  std::vector<std::string> words;
  std::string word;
  bool in_word = false;
  char quote = '\0';
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quote != '\0') {
      if (c == quote) quote = '\0';
      else if (c == '\\' && quote == '"' && i + 1 < line.size()) word += line[++i];
      else word += c;
      continue;
    }
    if (c == '#' && !in_word) break;  // a comment to the end of the line
    if (c == '\'' || c == '"') {
      quote = c;
      in_word = true;
    } else if (c == '\\' && i + 1 < line.size()) {
      word += line[++i];
      in_word = true;
    } else if (c == ' ' || c == '\t' || c == '\r') {
      if (in_word) words.push_back(word);
      word.clear();
      in_word = false;
    } else {
      word += c;
      in_word = true;
    }
  }
  if (quote != '\0') {
    error = "unterminated ";
    error += quote == '"' ? "double" : "single";
    error += " quote";
    return std::nullopt;
  }
  if (in_word) words.push_back(word);
  return words;
}

std::optional<Action> parse_command_line(const std::vector<std::string>& args, std::string& error) {
  CLI::App app{"tnvctl command"};
  app.require_subcommand(1);
  ActionSlot slot;
  add_device_commands(app, slot);
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last-first
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    error = cli::describe_parse_error(app, e);
    return std::nullopt;
  }
  if (!slot) {
    error = "no command";
    return std::nullopt;
  }
  return slot;
}

int run_action(const Action& action, Session& session) {
  Report report(session.options().json);
  int code = kExitOk;
  std::string error;
  try {
    if (action.check) action.check();
    code = action.run(session, report);
  } catch (const BadInput& e) {
    code = kExitBadInput;
    error = e.what();
  } catch (const std::exception& e) {  // RequestError, BusError, RunFailed, ...
    code = kExitFailure;
    error = e.what();
  }
  if (!error.empty()) std::fprintf(stderr, "tnvctl: %s: %s\n", action.name.c_str(), error.c_str());
  if (report.json_mode()) {
    report.data["command"] = action.name;
    report.data["ok"] = code == kExitOk;
    report.data["exit_code"] = code;
    if (!error.empty()) report.data["error"] = error;
    if (report.summary_on_stderr()) {
      std::cerr << report.data.dump() << '\n';
    } else {
      std::cout << (session.compact_json ? report.data.dump() : report.data.dump(2)) << '\n';
      std::cout.flush();
    }
  }
  return code;
}

std::uint8_t parse_axis(const std::string& name) {
  if (const std::optional<hal::Axis> a = hal::axis_from_name(name)) return static_cast<std::uint8_t>(hal::index(*a));
  std::string message = "axis must be " + std::string(hal::kAxisChoices) + ", not '";
  message.append(name).append("'");
  throw BadInput(message);
}

std::vector<std::string> axis_values_or(const std::string& every) {
  std::vector<std::string> out(hal::kAxisNames.begin(), hal::kAxisNames.end());
  out.push_back(every);
  return out;
}

std::string axis_help_or(const std::string& every) {
  std::string out;
  for (const char* name : hal::kAxisNames) out.append(out.empty() ? "" : ", ").append(name);
  return out + " or " + every;
}

const fw::can::ParamDef& param_named(const std::string& name) {
  if (const fw::can::ParamDef* p = can_host::find_param_by_text(name)) return *p;
  std::string message = "no parameter '";
  message.append(name).append("'");
  if (const std::string close = can_host::closest_param_name(name); !close.empty())
    message.append(" (did you mean ").append(close).append("?)");
  message += "; `tnvctl params list` shows them all";
  throw BadInput(message);
}

nlohmann::json firmware_json(const can_host::NodeIdentity& id) {
  return {{"version", can_host::firmware_version_text(id.firmware_version)},
          {"build_id", can_host::build_id_text(id.build_id)},
          {"protocol_version", id.protocol_version}};
}

std::string heartbeat_text(const can_host::Heartbeat& hb) {
  const nlohmann::json j = heartbeat_json(hb);
  std::string out = "state ";
  out.append(fw::to_string(hb.state)).append(", fault ").append(fw::to_string(hb.fault));
  if (!j["flags"].empty()) {
    out += ", flags";
    for (const auto& f : j["flags"]) out.append(" ").append(f.get<std::string>());
  }
  if (hb.overruns != 0) out.append(", overruns ").append(std::to_string(hb.overruns));
  if (hb.owner != 0) out.append(", command owner host ").append(std::to_string(hb.owner));
  return out;
}

void require_no_fault(const can_host::Heartbeat& hb, can_host::NodeClient& client, const std::string& what) {
  if (const std::optional<std::string> fault = can_host::fault_message(hb, client, what)) throw RunFailed(*fault);
}

}  // namespace tnv::tnvctl
