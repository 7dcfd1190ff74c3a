#pragma once
// The page's Program panel, server side: a program's preview (the path the
// interpreter makes of it from where the table stands, with the node's
// limits, as polylines the page draws), its run through run_gcode, and the
// summary the audit trail keeps of a program instead of its text.
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "tools/can/program_run.hpp"
#include "tools/serve/program_state.hpp"

namespace tnv::serve {

// A preview draws at most this many points; a longer path is thinned (the reply says so).
inline constexpr std::size_t kPreviewMaxPoints = 20'000;
// Arcs are drawn as chords of at most this angle (5 degrees).
inline constexpr double kPreviewArcStepRad = 0.0872664626;

// {"bytes", "lines", "sha256"}: what the audit trail logs of a program (sha256sum's digest of the text).
nlohmann::json program_summary(const std::string& gcode_text);

// The program as the page draws it:
// {"lines", "segments", "cycle_time_s", "length_mm", "tool_changes", "summary",
//  "start": [x, y], "travel": {"x": [min, max], "y": [min, max]},
//  "pieces": [{"line", "last_line", "points": [x0, y0, x1, y1, ...]}, ...],
//  "points", "thinned", "note"}. Each piece is one segment (line = its G-code
// line); past max_points, runs of consecutive segments share a piece (line
// .. last_line) and only every k-th point of it is kept.
nlohmann::json preview_json(const can_host::ProgramPlan& plan, std::size_t max_points = kPreviewMaxPoints);

// The refusal of a plan, or null when it may run: {"error", "line", "column"}.
nlohmann::json plan_refusal(const can_host::ProgramPlan& plan);

// The interpreter's setup a preview or run of the page asks for: the
// optional stop and block delete switches ("optional_stop", "block_delete":
// true or false, on when absent, as --optional-stop and --block-delete),
// the texts of a tool table and a parameter file ("tool_table",
// "var_file", as --tool-table and --var-file load them; 400 naming the
// line of a bad one),
// and a run from line N (docs/gcode.md "Run from line") from the body's optional
// "from_line" (1-based) with "from_pass", "tool_in_spindle",
// "approach_height_mm" and "clearance_z_mm", the options `tnvctl run
// --from-line` takes. Throws ApiError(400) for a field that is not a
// number (or switch) of its kind, or a companion without "from_line"; the values
// themselves (a line outside the program, one never run, ...) are refused
// by the interpreter, as for the command lines, before anything is sent.
gcode::CanonSetup page_canon_setup(const nlohmann::json& body);

// The page's program run on the node thread: run_gcode with the page's
// telemetry left as it is (no score: 1 ms telemetry would flood the
// scope), the run's progress and end into `state`, its interrupt flag as
// the stream's Ctrl-C, a pause continued by the Resume button
// (ProgramState::resume()), the scope fed by `scope` meanwhile. A program that
// cannot run throws ApiError(400) naming its line and column. `canon`: page_canon_setup;
// `tool_from_node`: ProgramRunOptions::tool_from_node (no "tool_in_spindle" in the request).
nlohmann::json run_program_for_page(can_host::NodeClient& client, const std::string& gcode_text,
                                    const gcode::CanonSetup& canon, bool tool_from_node, ProgramState& state,
                                    const can_host::FrameListener& scope);

}  // namespace tnv::serve
