#pragma once
// A G-code program for this XY table's motion queue (host side): the
// LinuxCNC dialect (canon_interpreter.hpp) run to its canonical calls, and
// the calls made segments (canon_segments.hpp). Every segment is checked
// against the firmware's limits exactly as the queue will check it, so a
// program that parses is a program the queue accepts; an error names the
// line (and the column where the interpreter found it) and no segment is
// returned.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "firmware/motion/motion_limits.hpp"
#include "firmware/motion/segment.hpp"
#include "firmware/motion/segment_geometry.hpp"
#include "tools/gcode/canon_interpreter.hpp"
#include "tools/gcode/gcode_error.hpp"
#include "tools/gcode/program_file.hpp"

namespace tnv::gcode {

using fw::motion::PlanePoint;

struct GcodeProgram;

struct GcodeOptions {
  PlanePoint start_mm{};           // where the machine is when the program starts (machine X Y Z)
  double rapid_feed_mm_s = 50.0;   // G0 path speed
  fw::motion::MotionLimits limits{};
  // The tool table, parameters (.var: work offsets, G28/G30, G92) and
  // subroutine path. A program ends at the end of its file too here (no
  // M2 needed, as LinuxCNC's task runs it); start_mm replaces its start_machine_mm.
  // With canon.from_line set it runs from that line, its approach starting
  // where the machine is (start_mm: the
  // from_line's own machine_position_mm is replaced).
  CanonSetup canon{};
  // A machine run's probe input: runs the program's segments so far, the
  // last a probe move (Segment::probe), and returns the probe's outcome;
  // the rest of the program is interpreted from it (docs/gcode.md "Probe
  // moves"). Unset: a probe line is refused.
  std::function<ProbeRun(const GcodeProgram& so_far)> run_probe;
};

// Why a program pauses (a Segment::pause): the operator continues it.
enum class PauseReason : std::uint8_t {
  program_stop,   // M0 (and G88's stop at the bottom of the bore)
  optional_stop,  // M1 with the optional stop switch on
  tool_change,    // M6: a manual tool change; the new tool's length applies from the next move
  pallet_change,  // M60: no pallet shuttle on this machine: the operator changes the part, a program stop
};
const char* to_string(PauseReason reason) noexcept;

struct ProgramPause {
  std::size_t segment = 0;  // index into GcodeProgram::segments
  PauseReason reason = PauseReason::program_stop;
  int tool = 0;  // tool_change: the tool now in the spindle
};

// "tool change (M6), tool 3", "program stop (M0)": the reason, and the tool for a tool change.
std::string to_string(const ProgramPause& pause);

struct GcodeProgram {
  std::vector<fw::motion::Segment> segments;           // tag = source line
  std::vector<fw::motion::SegmentGeometry> geometry;   // one per segment, with its start point
  bool ended = false;                                  // M2, M30 or the closing % seen
  std::size_t lines_run = 0;                           // CanonResult::lines_run
  std::size_t tool_changes = 0;                        // M6 (its length may apply to Z while Z does not move)
  std::vector<ProgramPause> pauses;                    // in program order: M0, M1 (switch on), M6
  std::size_t optional_stops_skipped = 0;              // M1 with the optional stop switch off
  std::size_t spindle_starts = 0;   // M3, M4 (and a canned cycle's restarts)
  std::size_t spindle_changes = 0;  // spindle elements sent (starts, new speeds, stops)
  // Calls this machine has nothing to do with (no coolant): counted and reported, not sent.
  std::size_t coolant_starts = 0;  // M7, M8
  std::size_t probes = 0;          // probe moves (G38.x) run on the machine
  double programmed_length_mm() const noexcept;
  // Sum of length / feed over the moves (rapids at the rapid feed); dwells add their time.
  double programmed_time_s() const noexcept;
};

struct GcodeResult {
  GcodeProgram program;
  std::optional<GcodeError> error;  // set: program is empty
};

// "L lines run, S segments, T tool changes, programmed cycle time X s",
// and what was not sent, if anything: the report line of tnvctl run and tnv-hil path.
std::string summary_text(const GcodeProgram& program);

GcodeResult parse_gcode(std::string_view text, const GcodeOptions& options = {});
// The file (read_program_file) as a program; subroutine files are looked
// for beside it first.
GcodeResult parse_gcode_file(const std::string& path, const GcodeOptions& options = {});

}  // namespace tnv::gcode
