#pragma once
// The scores as JSON, with the same keys from tnv-hil and tnvctl.
#include <nlohmann/json.hpp>

#include "tools/gcode/gcode_program.hpp"
#include "tools/score/contour_stats.hpp"
#include "tools/score/path_score.hpp"

namespace tnv::hil {

// {"max_um", "mean_um", "std_um", "samples"}.
nlohmann::json contour_stats_json(const ContourStats& s);
// The score keys of tnv-hil path and tnvctl run --json (path_score.hpp).
nlohmann::json path_score_json(const PathScore& s);
// What a program is, before it runs (tnv-hil path and tnvctl run --json):
// lines_run, segments, tool_changes, programmed_time_s, programmed_length_mm,
// and what was not sent (coolant_starts_not_sent).
nlohmann::json program_summary_json(const gcode::GcodeProgram& p);

}  // namespace tnv::hil
