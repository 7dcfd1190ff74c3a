// tnvctl script FILE|-: several commands on one session (with --emu, the
// emulated node lives only inside one process). Every line is parsed
// before the first is sent; the script stops at the first failure.
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "drivers/storage/regular_file.hpp"
#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

namespace {

constexpr std::size_t kMaxScriptBytes = 1u << 20;  // a bench script, not a data file

struct ScriptLine {
  int number = 0;
  std::string text;
  Action action;
};

std::string read_script(const std::string& path) {
  std::stringstream text;
  if (path == "-") {
    text << std::cin.rdbuf();
    return text.str();
  }
  std::string file;
  std::string error;
  if (!drivers::read_regular_file(path, kMaxScriptBytes, drivers::LinkPolicy::follow, file, error)) {
    throw BadInput(error);
  }
  return file;
}

int run_script(const std::string& path, Session& session, Report& report) {
  const std::string name = path == "-" ? "<stdin>" : path;
  std::vector<ScriptLine> lines;
  std::istringstream in(read_script(path));
  std::string text;
  bool needs_device = false;
  for (int number = 1; std::getline(in, text); ++number) {
    std::string error;
    const auto words = split_words(text, error);
    std::optional<Action> action;
    if (words && words->empty()) continue;  // blank or comment
    if (words) action = parse_command_line(*words, error);
    if (!action) {
      std::string message = name;
      message.append(":").append(std::to_string(number)).append(": ").append(error);
      throw BadInput(message);
    }
    needs_device = needs_device || action->needs_device;
    const auto first = text.find_first_not_of(" \t");
    lines.push_back({number, text.substr(first == std::string::npos ? 0 : first), std::move(*action)});
  }
  for (const ScriptLine& line : lines) {
    try {
      if (line.action.check) line.action.check();
    } catch (const BadInput& e) {
      std::string message = name;
      message.append(":").append(std::to_string(line.number)).append(": ").append(e.what());
      throw BadInput(message);
    }
  }
  if (needs_device && session.options().iface.empty() && !session.options().emu)
    throw BadInput("the script talks to a node: give --iface IFACE (SocketCAN) or --emu (the emulated controller)");
  session.compact_json = true;
  int done = 0;
  for (const ScriptLine& line : lines) {
    std::string echo = "> ";
    report.line(echo.append(line.text));
    const int code = run_action(line.action, session);
    if (code != kExitOk) {
      std::string message = name;
      message.append(":").append(std::to_string(line.number)).append(": '").append(line.text);
      message.append("' failed (exit ").append(std::to_string(code)).append("); the script stops here");
      report.data["lines_run"] = done;
      std::cerr << "tnvctl: " << message << '\n';
      // The failing command has printed its error; keep its exit code.
      return code;
    }
    ++done;
  }
  report.data["lines_run"] = done;
  return kExitOk;
}

}  // namespace

void add_script_commands(CLI::App& app, ActionSlot& slot) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "script", "run tnvctl commands from FILE (or - for stdin), one per line, # comments, on one session");
  cmd->add_option("file", *path, "script file, or - for stdin")->required();
  cmd->callback([&slot, path] {
    slot = Action{"script", false, [path](Session& s, Report& r) { return run_script(*path, s, r); }};
  });
}

}  // namespace tnv::tnvctl
