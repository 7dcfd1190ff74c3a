#pragma once
// The options every command that runs a G-code program takes, as `tnvctl
// gcode canon` takes them: --tool-table, --var-file, --subroutine-path,
// --block-delete, --optional-stop (tnvctl gcode canon, tnvctl run, tnv-hil path). Built as tnv_gcode_cli
// (tools/CMakeLists.txt): the G-code library itself needs no CLI11.
#include <string>
#include <vector>

#include "tools/gcode/canon_interpreter.hpp"
#include "tools/gcode/feed_hold_schedule.hpp"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace tnv::cli {

struct GcodeSetupOptions {
  std::string tool_table;  // .tbl
  std::string var_file;    // .var
  std::vector<std::string> subroutine_path;
  // The operator's block delete switch: "on" skips the lines that start
  // with '/', as LinuxCNC does by default; "off" runs them.
  std::string block_delete = "on";
  // The optional stop switch: "on" makes M1 pause a machine run (tnvctl
  // run, tnv-hil path) as M0 does, LinuxCNC's default; "off" runs through it.
  std::string optional_stop = "on";
};

// Run from line N (docs/gcode.md "Run from line"): --from-line, --from-pass,
// --clearance-z, --approach-height, --tool-in-spindle. Where the machine
// is comes from the caller (tnvctl gcode canon: --machine-position; a
// machine run: where the table stands).
struct FromLineOptions {
  int from_line = 0;  // 0: the whole program
  gcode::RunFromLine run_from;
  // --tool-in-spindle was given; without it a machine run takes the node's tool when the node knows it.
  bool tool_given = false;
};

// `options` must outlive the parse; the returned option is --from-line (for needs()).
CLI::Option* add_from_line_options(CLI::App& command, FromLineOptions& options);
// setup.from_line from the options (unset when --from-line is not given).
void apply_from_line(const FromLineOptions& options, gcode::CanonSetup& setup);

// The operator's feed holds on a schedule (tools/gcode/feed_hold_schedule.hpp):
// --hold-at S and --resume-at S, each repeatable, paired in order.
struct FeedHoldOptions {
  std::vector<double> hold_at_s;
  std::vector<double> resume_at_s;
};
// `options` must outlive the parse.
void add_feed_hold_options(CLI::App& command, FeedHoldOptions& options);

// `options` must outlive the parse.
void add_gcode_setup_options(CLI::App& command, GcodeSetupOptions& options);

// The files loaded into a setup (load_tool_table_file, load_var_file) and
// the subroutine path and block delete switch set; false with `error` ("<path>: line N: why").
bool load_gcode_setup(const GcodeSetupOptions& options, gcode::CanonSetup& setup, std::string& error);

}  // namespace tnv::cli
