// tnv-hil: hardware-in-the-loop runs of the TNV-40 firmware on the emulated
// I/O board and table. The command families live in *_commands.cpp.
#include <CLI/CLI.hpp>

#include "tools/cli/cli_frame.hpp"
#include "tools/tnv-hil/commands.hpp"

int main(int argc, char** argv) {
  using namespace tnv::cli;
  CLI::App app{"tnv-hil: run the TNV-40 firmware against the emulated I/O board and table"};
  app.require_subcommand(1);
  tnv::cli::add_version_flag(app, "tnv-hil");
  Runner run;
  add_circle_commands(app, run);
  add_path_commands(app, run);
  add_best_circle_commands(app, run);
  add_fault_commands(app, run);
  add_soak_commands(app, run);
  add_boring_commands(app, run);
  add_arsc_commands(app, run);
  add_shaper_commands(app, run);
  add_rt_budget_commands(app, run);
  add_bus_stress_commands(app, run);
  add_homing_commands(app, run);
  add_spindle_commands(app, run);
  add_screw_commands(app, run);
  add_freq_response_commands(app, run);
#ifdef TNV_HAVE_CAMPAIGN
  add_campaign_commands(app, run);
#endif

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return tnv::cli::report_parse_error(app, e, "tnv-hil", kExitBadInput);
  }
  return run ? run() : kExitBadInput;
}
