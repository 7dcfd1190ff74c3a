// boring: S4 adaptive boring (tnv-hil boring --planner direct): the
// firmware's infeed planner, in this process at the node's resolution,
// plans every part the emulated process cuts; its gauge noise is drawn
// from the run's seed. The planner's settings are the node's bore.*
// parameters (planner and process share bore.sigma_d_mm, as in the
// paper); the scenario's bore gauge ([noise] bore_gauge_*) adds to it.
// No axis loops run: `controllers` is refused and rows say "none".
#include "tools/campaign/experiment.hpp"
#include "tools/campaign/manifest.hpp"
#include "tools/hil/boring_run.hpp"

namespace tnv::campaign {

namespace {

hil::BoringRunRequest boring_request(const fw::BoringStationSettings& bore, const nlohmann::ordered_json& settings,
                                     const emu::Scenario& scenario) {
  const fw::BoringPlannerParams planner = fw::planner_params(bore);
  hil::BoringRunRequest r = hil::paper_boring_request(planner.sigma_d_mm, planner.alpha0);
  r.planner = planner;
  r.positions_mm = {bore.top_overhang_mm, bore.bottom_overhang_mm};
  r.parts = settings.at("parts").get<int>();
  r.change_at = settings.at("change_at").get<std::vector<int>>();
  return hil::with_scenario_gauge(r, scenario);
}

std::string check_boring_settings(const nlohmann::ordered_json& settings, const std::string&, std::string& key) {
  const std::int64_t parts = settings.at("parts").get<std::int64_t>();
  if (parts < 1 || parts > 100'000) {
    key = "parts";
    return "must be in 1..100000";
  }
  if (settings.at("change_at").size() > 2) {
    key = "change_at";
    return "at most two change points (the paper's three parameter sets)";
  }
  const std::string error =
      hil::validate_boring_request(boring_request(fw::can::default_node_settings().bore, settings, emu::Scenario{}));
  if (error.empty()) return {};
  // "change_at: ..." names the key already.
  for (const char* k : {"change_at", "parts"}) {
    const std::string prefix = std::string(k) + ": ";
    if (error.rfind(prefix, 0) == 0) {
      key = k;
      return error.substr(prefix.size());
    }
  }
  key = "parts";
  return error;
}

// What reaches a part: the planner's bore.* parameters and the bore gauge.
std::string check_boring_input(const std::string& name, bool is_parameter) {
  if (is_parameter) return name.rfind("bore.", 0) == 0 ? "" : "boring runs only the planner: vary bore.* parameters";
  if (name == "noise.bore_gauge_um_rms" || name == "noise.bore_gauge_resolution_um") return {};
  return "no other scenario key than noise.bore_gauge_um_rms and noise.bore_gauge_resolution_um reaches a bored "
         "part";
}

void run_boring_row(const RunContext& c, nlohmann::ordered_json& row) {
  const hil::BoringRunRequest request = boring_request(c.setup.bore, c.manifest.settings, *c.setup.scenario);
  if (const std::string error = hil::validate_boring_request(request); !error.empty()) {
    row["status"] = "error";
    row["reason"] = error;
    return;
  }
  const hil::BoringRunResult r = hil::run_boring(request, static_cast<std::uint64_t>(c.run.seed));
  if (!r.error.empty()) {
    row["status"] = "error";
    row["reason"] = r.error;
    return;
  }
  row["status"] = "ok";
  row["bad_parts"] = r.bad_parts;
  row["resets"] = r.resets;
  row["deflection_rms_mm"] = r.deflection_rms_mm;
}

}  // namespace

const Experiment& boring_experiment() {
  static const Experiment e = [] {
    Experiment x;
    x.name = "boring";
    x.controllers = ControllerUse::none;
    x.settings = {{"parts", SettingType::integer, false, 30},
                  {"change_at", SettingType::integer_list, false, nlohmann::ordered_json::array({11, 21})}};
    x.results = {{"bad_parts", "INTEGER"}, {"resets", "INTEGER"}, {"deflection_rms_mm", "REAL"}};
    x.default_metric = "bad_parts";
    x.check_settings = check_boring_settings;
    x.check_input = check_boring_input;
    x.base_settings = default_base_settings;
    x.run = run_boring_row;
    return x;
  }();
  return e;
}

}  // namespace tnv::campaign
