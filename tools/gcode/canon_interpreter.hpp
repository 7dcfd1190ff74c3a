#pragma once
// LinuxCNC-dialect RS274/NGC interpreter (host side): a program becomes the
// canonical machine calls LinuxCNC's interpreter makes for it, one per
// line in the NAME(args) form its standalone `rs274` prints, so the two can
// be compared call by call (docs/gcode.md). The interpreter knows Z, the
// spindle, coolant, tools and offsets even where this machine cannot move
// them yet. An error names line and column, and no call is returned.
// interpret_canon_to hands each call to a sink as it is made, so nothing
// holds them all: what a sink received from a run that ends in an error
// is to be dropped (the calls up to the refused line).
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tools/gcode/gcode_error.hpp"
#include "tools/gcode/ngc_parameters.hpp"
#include "tools/gcode/tool_table.hpp"

namespace tnv::gcode {

// What a call does, for a machine to run it (canon_segments.hpp): filled
// where the call's text is made. Machine coordinates (offsets and tool
// length applied) in millimetres whatever the program's units; the text
// keeps rs274's form (program coordinates, program units).
struct CanonMotion {
  enum class Kind : std::uint8_t {
    other,        // no motion and nothing a machine run counts (modes, offsets, comments, ...)
    traverse,     // STRAIGHT_TRAVERSE: end_mm
    feed,         // STRAIGHT_FEED: end_mm
    arc,          // ARC_FEED: end_mm, centre_mm, plane, turn
    probe,        // STRAIGHT_PROBE: end_mm; value = 2, 3, 4, 5 for G38.2 .. G38.5
    spline,       // NURBS_FEED (G5.1): end_mm
    rigid_tap,    // RIGID_TAP (G33.1): end_mm, the bottom (the tap returns to its start)
    dwell,        // DWELL: value = seconds
    feed_rate,    // SET_FEED_RATE: value = mm per minute
    tool_change,  // CHANGE_TOOL: value = the tool now in the spindle
    spindle_on,   // START_SPINDLE_CLOCKWISE (value 1) / _COUNTERCLOCKWISE (value -1)
    spindle_speed,  // SET_SPINDLE_SPEED: value = rpm (G97; G96 is refused)
    spindle_stop,   // STOP_SPINDLE_TURNING: value 1 at the program's end (M2, M30), else 0
    coolant_on,   // MIST_ON / FLOOD_ON
    pause,        // PROGRAM_STOP (M0, G88's stop): value 0; OPTIONAL_PROGRAM_STOP (M1): value 1; M60's PROGRAM_STOP: 60
    end,          // PROGRAM_END (M2, M30) / FINISH (the closing %)
  };
  Kind kind = Kind::other;
  std::array<double, 3> end_mm{};     // X Y Z
  std::array<double, 3> centre_mm{};  // arc: X Y Z, the coordinate along the arc's axis that of its end
  int plane = 17;                     // arc: 17 XY, 18 XZ, 19 YZ
  int turn = 0;                       // arc: > 0 counterclockwise; |turn| - 1 full turns before the end
  double value = 0.0;
};

struct CanonCall {
  int line = 0;      // source line (1-based); 0 for the start-up calls
  std::string text;  // e.g. STRAIGHT_FEED(1.0000, 2.0000, 0.0000, 0.0000, 0.0000, 0.0000)
  CanonMotion motion{};
  std::uint32_t file = 0;  // 0: the program's line; k: a line of CanonResult::files[k - 1]
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

// A probe move run on a machine (CanonSetup::probe_input): how it ended.
// Positions in machine coordinates, mm (X Y Z).
struct ProbeRun {
  bool tripped = false;
  std::array<double, 3> trip_mm{};  // tripped: where the probe changed state
  std::array<double, 3> rest_mm{};  // where the machine rests after it: the program goes on from here
  std::string error;  // set: the probe failed (G38.2/G38.4 without a change, ...): the program stops at its line
};
// Runs the probe move of the call just made (STRAIGHT_PROBE, kind probe) on the
// machine and returns when its outcome is known.
using ProbeInput = std::function<ProbeRun(const CanonCall& probe)>;

struct CanonSetup {
  ToolTable tools;           // lengths in millimetres (this machine's units)
  NgcParameters parameters;  // from a .var file: work offsets, G28/G30 homes, G92
  bool block_delete = true;  // '/' lines skipped (LinuxCNC's default: the switch on)
  // The optional stop switch: M1 pauses a machine run (canon_segments.hpp)
  // only while it is on (LinuxCNC's default). The calls are the same
  // either way: rs274 prints OPTIONAL_PROGRAM_STOP whatever the switch.
  bool optional_stop = true;
  // Where a call of o<name> that the program does not define finds name.ngc,
  // in order (ngc_subroutine_files.hpp); interpret_canon_file puts the
  // program's own directory first.
  std::vector<std::string> subroutine_path;
  // A loop that never ends is an error after this many lines run, not a hang.
  std::size_t max_lines_run = 20'000'000;
  std::optional<RunFromLine> from_line;  // unset: run the whole program
  // Where the machine is when a full run starts (machine coordinates, mm).
  std::array<double, 3> start_machine_mm{};
  // A machine run ends at the end of the file as LinuxCNC's task does; rs274
  // (and so the canon text compared with it) refuses a file with no M2, M30
  // or closing %.
  bool end_of_file_ends = false;
  // Unset: a probe move as the standalone rs274 models it (no probe input:
  // it never trips; docs/gcode.md). Set: the interpreter waits at each
  // probe for the machine's outcome and sets #5061-#5070 and the current
  // position from it, as LinuxCNC does.
  ProbeInput probe_input;
};

// Receives each call as it is made, in order.
using CanonSink = std::function<void(const CanonCall&)>;

struct CanonRun {
  std::vector<std::string> files;  // the subroutine files read, as CanonCall::file names them
  std::size_t lines_run = 0;  // lines read and run (a loop's lines once per pass), from the start line
  std::optional<GcodeError> error;  // set: the calls the sink received are not the program's (drop them)
};

struct CanonResult : CanonRun {
  std::vector<CanonCall> calls;  // empty when error is set
};

// Holds the program's lines (as views into `text`: ngc_program_lines.hpp)
// and the interpreter's state, never the calls.
CanonRun interpret_canon_to(std::string_view text, const CanonSetup& setup, const CanonSink& sink);
// interpret_canon_to with every call collected.
CanonResult interpret_canon(std::string_view text, const CanonSetup& setup = {});
// The calls as text, one NAME(args) a line.
std::string canon_text(const std::vector<CanonCall>& calls);
// The file as a program (read_program_file), or an error at line 0;
// subroutine files are looked for beside it first (add_program_directory).
CanonRun interpret_canon_file_to(const std::string& path, const CanonSetup& setup, const CanonSink& sink);
CanonResult interpret_canon_file(const std::string& path, const CanonSetup& setup = {});
// Puts the program's own directory first on setup.subroutine_path.
void add_program_directory(CanonSetup& setup, const std::string& program_path);
// Loads a .tbl / .var file into `setup`; false with `error` ("<path>: line N: why").
bool load_tool_table_file(const std::string& path, CanonSetup& setup, std::string& error);
bool load_var_file(const std::string& path, CanonSetup& setup, std::string& error);

}  // namespace tnv::gcode
