#pragma once
// LinuxCNC-dialect RS274/NGC interpreter (host side): a program becomes the
// canonical machine calls LinuxCNC's interpreter makes for it, one per
// line in the NAME(args) form its standalone `rs274` prints, so the two can
// be compared call by call (docs/gcode.md). The interpreter knows Z, the
// spindle, coolant, tools and offsets even where this machine cannot move
// them yet. An error names line and column, and no call is returned.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tools/gcode/gcode_program.hpp"
#include "tools/gcode/ngc_parameters.hpp"
#include "tools/gcode/tool_table.hpp"

namespace tnv::gcode {

struct CanonCall {
  int line = 0;      // source line (1-based); 0 for the start-up calls
  std::string text;  // e.g. STRAIGHT_FEED(1.0000, 2.0000, 0.0000, 0.0000, 0.0000, 0.0000)
};

// Run from line N (docs/gcode.md "Run from line"): the lines before the
// start run silently (parameters, O-word flow, offsets, tools, modes; no
// motion, dwell, pause or message), then the modal state is made again as
// calls and the tool approaches the start point: Z up to the clearance,
// XY at rapid, down at rapid to `approach_mm` above the start, the rest at
// the feed rate in force. From there the calls are those of a full run.
struct RunFromLine {
  int line = 0;   // 1-based source line
  long pass = 1;  // start the pass-th time that line runs (a line in a loop)
  // Machine Z (the spindle nose) of the first retract; 0 is the top of Z's
  // travel on this machine (docs/machine.md), where Z homes.
  double clearance_z_mm = 0.0;
  double approach_mm = 5.0;  // the last part of the way down runs at the feed rate
  // Where the machine is when the run starts (machine coordinates, mm) and
  // the tool it holds; a full run assumes the same (0, 0, 0 and no tool).
  std::array<double, 3> machine_position_mm{};
  int tool_in_spindle = 0;
};

struct CanonSetup {
  ToolTable tools;           // lengths in millimetres (this machine's units)
  NgcParameters parameters;  // from a .var file: work offsets, G28/G30 homes, G92
  bool block_delete = true;  // '/' lines skipped (LinuxCNC's default: the switch on)
  // Where a call of o<name> that the program does not define finds name.ngc,
  // in order (ngc_subroutine_files.hpp); interpret_canon_file puts the
  // program's own directory first.
  std::vector<std::string> subroutine_path;
  // A loop that never ends is an error after this many lines run, not a hang.
  std::size_t max_lines_run = 20'000'000;
  std::optional<RunFromLine> from_line;  // unset: run the whole program
};

struct CanonResult {
  std::vector<CanonCall> calls;
  std::optional<GcodeError> error;  // set: calls is empty
};

CanonResult interpret_canon(std::string_view text, const CanonSetup& setup = {});
// The calls as text, one NAME(args) a line.
std::string canon_text(const std::vector<CanonCall>& calls);
// The file as a program (read_program_file), or an error at line 0.
CanonResult interpret_canon_file(const std::string& path, const CanonSetup& setup = {});
// Loads a .tbl / .var file into `setup`; false with `error` ("<path>: line N: why").
bool load_tool_table_file(const std::string& path, CanonSetup& setup, std::string& error);
bool load_var_file(const std::string& path, CanonSetup& setup, std::string& error);

}  // namespace tnv::gcode
