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

void add_feed_hold_options(CLI::App& command, FeedHoldOptions& o) {
  command
      .add_option("--hold-at", o.hold_at_s,
                  "hold the feed this many seconds after the program starts (repeatable, each with a --resume-at): "
                  "the table brakes on the path and waits, the spindle keeps turning")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  command
      .add_option("--resume-at", o.resume_at_s,
                  "resume the feed held by the --hold-at before it, seconds after the program starts (repeatable)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

CLI::Option* add_from_line_options(CLI::App& command, FromLineOptions& o) {
  CLI::Option* from_line = command.add_option("--from-line", o.from_line,
                    "run from this line (1-based): the lines before run silently, the modal state is made again and "
                    "the tool approaches the start (docs/gcode.md \"Run from line\")")
      ->check(CLI::PositiveNumber);
  command.add_option("--from-pass", o.run_from.pass, "with --from-line: start the Nth time the line runs (in a loop)")
      ->check(CLI::PositiveNumber)
      ->needs(from_line);
  command.add_option("--clearance-z", o.run_from.clearance_z_mm,
                     "with --from-line: machine Z (mm) of the first retract (default 0: the top of Z's travel)")
      ->needs(from_line);
  command.add_option("--approach-height", o.run_from.approach_mm,
                     "with --from-line: the last mm above the start point go at the feed rate (default 5)")
      ->check(CLI::NonNegativeNumber)
      ->needs(from_line);
  command.add_option("--tool-in-spindle", o.run_from.tool_in_spindle,
                     "with --from-line: the tool the machine holds (default: tnvctl run asks the node, which knows "
                     "it after a confirmed M6; else 0, none); another is changed at the start")
      ->check(CLI::NonNegativeNumber)
      ->each([&o](const std::string&) { o.tool_given = true; })
      ->needs(from_line);
  return from_line;
}

void apply_from_line(const FromLineOptions& o, gcode::CanonSetup& setup) {
  if (o.from_line == 0) return;
  setup.from_line = o.run_from;
  setup.from_line->line = o.from_line;
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
