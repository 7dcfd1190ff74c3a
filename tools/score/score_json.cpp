#include "tools/score/score_json.hpp"

namespace tnv::hil {

nlohmann::json contour_stats_json(const ContourStats& s) {
  return {{"max_um", s.max_um}, {"mean_um", s.mean_um}, {"std_um", s.std_um}, {"samples", s.samples}};
}

nlohmann::json path_score_json(const PathScore& s) {
  return {{"contour_error_max_um", s.contour_error_max_um}, {"contour_error_mean_um", s.contour_error_mean_um},
          {"contour_error_std_um", s.contour_error_std_um}, {"path_deviation_max_um", s.path_deviation_max_um},
          {"accel_ratio_max", s.accel_ratio_max},           {"jerk_ratio_max", s.jerk_ratio_max},
          {"feed_ratio", s.feed_ratio},                     {"cycle_time_s", s.cycle_time_s}};
}

nlohmann::json program_summary_json(const gcode::GcodeProgram& p) {
  return {{"lines_run", p.lines_run},
          {"segments", p.segments.size()},
          {"tool_changes", p.tool_changes},
          {"program_pauses", p.pauses.size()},
          {"optional_stops_skipped", p.optional_stops_skipped},
          {"programmed_time_s", p.programmed_time_s()},
          {"programmed_length_mm", p.programmed_length_mm()},
          {"spindle_starts", p.spindle_starts},
          {"spindle_commands", p.spindle_changes},
          {"coolant_starts_not_sent", p.coolant_starts}};
}

}  // namespace tnv::hil
