#include "tools/cli/cli_frame.hpp"

#include <cstdio>
#include <vector>
#include <string>

#include "tools/cli/tnv_version.hpp"

namespace tnv::cli {

std::string version_text(const char* tool) { return std::string(tool) + " " + kProjectVersion; }

void add_version_flag(CLI::App& app, const char* tool) {
  app.set_version_flag("--version", version_text(tool), "print the version and exit");
}

namespace {

std::string command_list(const CLI::App& app) {
  std::string out;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (!out.empty()) out += ", ";
    out += sub->get_name();
  }
  return out;
}

}  // namespace

std::string describe_parse_error(CLI::App& app, const CLI::ParseError& e) {
  const bool has_commands = !app.get_subcommands([](const CLI::App*) { return true; }).empty();
  const bool no_command = has_commands && app.get_subcommands().empty();
  const std::vector<std::string> left = app.remaining();
  if (no_command && !left.empty() && !left.front().empty() && left.front()[0] != '-')
    return "unknown command '" + left.front() + "' (the commands: " + command_list(app) + ")";
  if (no_command && dynamic_cast<const CLI::RequiredError*>(&e) != nullptr && left.empty())
    return "which command? (the commands: " + command_list(app) + ")";
  const std::string what = e.what();
  return what.empty() ? "bad command line" : what;
}

int report_parse_error(CLI::App& app, const CLI::ParseError& e, const char* tool, int bad_input_code) {
  if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);  // help, --version
  std::fprintf(stderr, "%s: %s\nRun '%s --help' for more information.\n", tool, describe_parse_error(app, e).c_str(),
               tool);
  return bad_input_code;
}

}  // namespace tnv::cli
