#include "tools/cli/gcode_setup_options.hpp"

#include <CLI/CLI.hpp>

namespace tnv::cli {

void add_gcode_setup_options(CLI::App& command, GcodeSetupOptions& options) {
  command.add_option("--tool-table", options.tool_table, "a LinuxCNC tool table (.tbl), lengths in millimetres");
  command.add_option("--var-file", options.var_file, "a LinuxCNC parameter file (.var): work offsets, G28/G30, G92");
  command
      .add_option("--subroutine-path", options.subroutine_path,
                  "a directory where o<name> call finds name.ngc, after the program's own directory (repeatable)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->check(CLI::ExistingDirectory);
  command
      .add_option("--block-delete", options.block_delete,
                  "the block delete switch: on skips the lines that start with '/' (LinuxCNC's default), off runs them")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  command
      .add_option("--optional-stop", options.optional_stop,
                  "the optional stop switch: on makes M1 pause a machine run as M0 does (LinuxCNC's default), off "
                  "runs through it; the canon calls are the same either way")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
}

bool load_gcode_setup(const GcodeSetupOptions& options, gcode::CanonSetup& setup, std::string& error) {
  if (!options.tool_table.empty() && !gcode::load_tool_table_file(options.tool_table, setup, error)) return false;
  if (!options.var_file.empty() && !gcode::load_var_file(options.var_file, setup, error)) return false;
  setup.subroutine_path = options.subroutine_path;
  setup.block_delete = options.block_delete != "off";
  setup.optional_stop = options.optional_stop != "off";
  return true;
}

}  // namespace tnv::cli
