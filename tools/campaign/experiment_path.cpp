// path: a G-code program (tnv-hil path FILE) run by the firmware on the
// emulated table and scored against its exact programmed geometry. The
// program is copied into the campaign directory when it is planned.
#include "tools/campaign/experiment.hpp"
#include "tools/campaign/manifest.hpp"
#include "tools/gcode/gcode_program.hpp"
#include "tools/gcode/probe_outcome.hpp"
#include "tools/hil/path_run.hpp"
#include "tools/hil/seeded_scenario.hpp"
#include "tools/score/score_json.hpp"

namespace tnv::campaign {

namespace {

constexpr double kMinRapidFeedMmS = 0.01;  // tnv-hil path --rapid-feed's range
constexpr double kMaxRapidFeedMmS = 1000.0;

std::string check_path_settings(const nlohmann::ordered_json& settings, const std::string& program_text,
                                std::string& key) {
  const double rapid = settings.at("rapid_feed_mm_s").get<double>();
  if (!(rapid >= kMinRapidFeedMmS && rapid <= kMaxRapidFeedMmS)) {
    key = "rapid_feed_mm_s";
    return "must be in 0.01..1000 mm/s";
  }
  // Read for a table at the origin: a G-code error does not depend on
  // where the table stands (the run reads it again from where it holds).
  gcode::GcodeOptions options;
  options.rapid_feed_mm_s = rapid;
  options.run_probe = gcode::untouched_probe;  // as if no probe tripped: the run reads on from each result
  const gcode::GcodeResult parsed = gcode::parse_gcode(program_text, options);
  if (parsed.error) {
    key = "program";
    return settings.at("program").get<std::string>() + ": " + gcode::to_string(*parsed.error);
  }
  if (parsed.program.segments.empty()) {
    key = "program";
    return settings.at("program").get<std::string>() + ": no motion";
  }
  return {};
}

void run_path_row(const RunContext& c, nlohmann::ordered_json& row) {
  hil::PathRunOptions options;
  options.rapid_feed_mm_s = c.manifest.settings.at("rapid_feed_mm_s").get<double>();
  const hil::PathRunResult r = hil::run_path(hil::seeded(*c.setup.scenario, c.run.seed), *c.setup.config,
                                             *c.run.controller, c.manifest.program_text, options);
  if (!r.completed) {
    row["status"] = r.timed_out ? "timeout" : r.faulted ? "fault" : "error";
    row["reason"] = r.error;
    return;
  }
  row["status"] = "ok";
  const nlohmann::json score = hil::path_score_json(r.score);
  for (const auto& [key, value] : score.items())
    if (row.contains(key)) row[key] = value;
  row["underruns"] = r.underruns;
  row["segments"] = r.segments;
  row["programmed_length_mm"] = r.programmed_length_mm;
}

}  // namespace

const Experiment& path_experiment() {
  static const Experiment e = [] {
    Experiment x;
    x.name = "path";
    x.controllers = ControllerUse::choose;
    x.settings = {{"program", SettingType::string, true, nullptr},
                  {"rapid_feed_mm_s", SettingType::number, false, 50.0}};
    for (const char* k : {"contour_error_max_um", "contour_error_mean_um", "contour_error_std_um", "path_deviation_max_um",
                          "accel_ratio_max", "jerk_ratio_max", "feed_ratio", "cycle_time_s"})
      x.results.push_back({k, "REAL"});
    x.results.push_back({"underruns", "INTEGER"});
    x.results.push_back({"segments", "INTEGER"});
    x.results.push_back({"programmed_length_mm", "REAL"});
    x.default_metric = "contour_error_max_um";
    x.check_settings = check_path_settings;
    x.check_input = any_input;
    x.base_settings = default_base_settings;
    x.run = run_path_row;
    return x;
  }();
  return e;
}

}  // namespace tnv::campaign
