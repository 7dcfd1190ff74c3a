// arsc tick: the robust ARSC as the firmware's feed-override source on the
// emulated TNV-40 (tnv-hil arsc tick --period-ms N): a test stage fits the
// loop's model, then the table cuts the study's program at 150 N. The
// study sets the firmware's arsc.* parameters and path limits itself and
// runs R-DVSC+DDC; its [milling] replaces the table's. What a campaign
// varies is the table: plant, noise, transport (scenario keys).
#include "firmware/adaptive/arsc/pole_sets.hpp"
#include "tools/campaign/experiment.hpp"
#include "tools/campaign/manifest.hpp"
#include "tools/hil/arsc_tick_json.hpp"
#include "tools/hil/arsc_tick_study.hpp"
#include "tools/hil/seeded_scenario.hpp"

namespace tnv::campaign {

namespace {

std::string check_arsc_tick_settings(const nlohmann::ordered_json& settings, const std::string&, std::string& key) {
  const std::int64_t period = settings.at("period_ms").get<std::int64_t>();
  if (period < 1 || period > 500) {
    key = "period_ms";
    return "must be a whole number of 1 ms ticks in 1..500";
  }
  if (!fw::arsc::parse_pole_set(settings.at("poles").get<std::string>())) {
    key = "poles";
    return "must be \"case1\", \"case2\", \"case3\" or \"case4\" (S3 Fig. 7)";
  }
  if (!hil::parse_study_path(settings.at("path").get<std::string>())) {
    key = "path";
    return "must be \"line\" or \"arc\"";
  }
  const double speedup = settings.at("speedup").get<double>();
  if (!(speedup >= 0.1 && speedup <= 20.0)) {
    key = "speedup";
    return "must be in 0.1..20";
  }
  return {};
}

std::string check_arsc_tick_input(const std::string& name, bool is_parameter) {
  if (is_parameter) return "the study sets the firmware's arsc.* parameters and path limits itself; vary the table";
  if (name.rfind("milling.", 0) == 0) return "the study's milling force replaces the table's [milling]";
  return {};
}

void run_arsc_tick_row(const RunContext& c, nlohmann::ordered_json& row) {
  const nlohmann::ordered_json& s = c.manifest.settings;
  hil::TickStudyConfig config;
  config.table = hil::seeded(*c.setup.scenario, c.run.seed);
  config.poles = *fw::arsc::parse_pole_set(s.at("poles").get<std::string>());
  config.path = *hil::parse_study_path(s.at("path").get<std::string>());
  config.ticks_per_sample = s.at("period_ms").get<std::uint32_t>();
  config.pole_speedup = s.at("speedup").get<double>();
  config.adapt = !s.at("fixed_gain").get<bool>();
  config.label = std::to_string(config.ticks_per_sample) + " ms";
  const hil::TickStudyResult r = hil::run_tick_study(config);
  if (!r.error.empty() || !r.fault.empty()) {
    row["status"] = r.error.empty() ? "fault" : "error";
    row["reason"] = r.error.empty() ? r.fault : r.error;
    return;
  }
  row["status"] = "ok";
  const nlohmann::json j = hil::tick_study_json(r);
  for (const auto& [key, value] : j.items())
    if (row.contains(key) && key != "status" && key != "reason") row[key] = value;
}

}  // namespace

const Experiment& arsc_tick_experiment() {
  static const Experiment e = [] {
    Experiment x;
    x.name = "arsc tick";
    x.controllers = ControllerUse::rdvsc_only;
    x.settings = {{"period_ms", SettingType::integer, false, 1},
                  {"poles", SettingType::string, false, "case1"},
                  {"path", SettingType::string, false, "line"},
                  {"speedup", SettingType::number, false, 1.0},
                  {"fixed_gain", SettingType::boolean, false, false}};
    x.results = {{"force_error_max_pct", "REAL"},      {"force_error_rms_pct", "REAL"},
                 {"force_error_true_max_pct", "REAL"}, {"force_error_true_rms_pct", "REAL"},
                 {"force_error_max_at_s", "REAL"},     {"diverged", "INTEGER"},
                 {"diverged_at_s", "REAL"},            {"dac_saturated_ticks", "INTEGER"},
                 {"dac_saturated_fraction", "REAL"},   {"command_clamped_after_settle", "INTEGER"},
                 {"refused_gain_updates", "INTEGER"},  {"refused_segments", "INTEGER"},
                 {"max_abs_gain", "REAL"},             {"override_min_seen", "REAL"},
                 {"override_max_seen", "REAL"},        {"max_feed_mm_s", "REAL"},
                 {"travel_mm", "REAL"}};
    x.default_metric = "force_error_max_pct";
    x.check_settings = check_arsc_tick_settings;
    x.check_input = check_arsc_tick_input;
    x.base_settings = default_base_settings;
    x.run = run_arsc_tick_row;
    return x;
  }();
  return e;
}

}  // namespace tnv::campaign
