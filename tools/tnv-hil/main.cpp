// tnv-hil: hardware-in-the-loop runs of the TNV-40 firmware on the emulated
// I/O board and table. The command families live in *_commands.cpp.
#include <CLI/CLI.hpp>
#include <array>
#include <string>

#include "tools/cli/cli_frame.hpp"
#include "tools/tnv-hil/commands.hpp"

namespace {

using AddCommands = void (*)(CLI::App&, tnv::cli::Runner&);

// In the order --help lists them.
constexpr std::array kCommandFamilies{
    &tnv::cli::add_circle_commands,     &tnv::cli::add_path_commands,   &tnv::cli::add_best_circle_commands,
    &tnv::cli::add_fault_commands,      &tnv::cli::add_soak_commands,   &tnv::cli::add_boring_commands,
    &tnv::cli::add_arsc_commands,       &tnv::cli::add_shaper_commands, &tnv::cli::add_rt_budget_commands,
    &tnv::cli::add_bus_stress_commands, &tnv::cli::add_homing_commands, &tnv::cli::add_spindle_commands,
    &tnv::cli::add_screw_commands,      &tnv::cli::add_freq_response_commands,
#ifdef TNV_HAVE_CAMPAIGN
    &tnv::cli::add_campaign_commands,
#endif
};

bool has_command(const CLI::App& app, const std::string& name) {
  return !app.get_subcommands([&name](const CLI::App* sub) { return sub->check_name(name); }).empty();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace tnv::cli;
  CLI::App app{"tnv-hil: run the TNV-40 firmware against the emulated I/O board and table"};
  app.require_subcommand(1);
  tnv::cli::add_version_flag(app, "tnv-hil");
  Runner run;
  // A named command builds the families' option trees only up to its own:
  // building and freeing all of them was a third of a process's start
  // (docs/performance.md). Anything else (--help, --version, a typo) gets all.
  const std::string first = argc > 1 ? argv[1] : "";
  const bool named = !first.empty() && first.front() != '-';
  for (AddCommands add : kCommandFamilies) {
    add(app, run);
    if (named && has_command(app, first)) break;
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return tnv::cli::report_parse_error(app, e, "tnv-hil", kExitBadInput);
  }
  return run ? run() : kExitBadInput;
}
