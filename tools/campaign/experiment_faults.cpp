// faults: one injected fault of the safety table (tnv-hil faults --only
// NAME) on each run's machine: what the supervisor latched, how fast the
// board's outputs were safe, and whether the case's verdict is met.
// Latching the injected fault is this experiment's result, not a failed
// run: the status is "ok" whenever the case ran; its `ok` says met or not.
#include <optional>

#include "tools/campaign/experiment.hpp"
#include "tools/campaign/manifest.hpp"
#include "tools/hil/fault_verdict.hpp"
#include "tools/hil/seeded_scenario.hpp"

namespace tnv::campaign {

namespace {

std::optional<hil::FaultCase> fault_case_named(const std::string& name) {
  for (const hil::FaultCase& c : hil::standard_fault_cases())
    if (c.name == name) return c;
  return std::nullopt;
}

std::string check_fault_settings(const nlohmann::ordered_json& settings, const std::string&, std::string& key) {
  const std::string name = settings.at("fault_case").get<std::string>();
  if (fault_case_named(name)) return {};
  std::string names;
  for (const hil::FaultCase& c : hil::standard_fault_cases()) names += (names.empty() ? "" : ", ") + c.name;
  key = "fault_case";
  return "\"" + name + "\": no such fault case (" + names + ")";
}

void run_faults_row(const RunContext& c, nlohmann::ordered_json& row) {
  const hil::FaultCase fault_case = *fault_case_named(c.manifest.settings.at("fault_case").get<std::string>());
  const emu::Scenario scenario = hil::seeded(*c.setup.scenario, c.run.seed);
  const hil::FaultObservation obs =
      hil::run_fault_case(scenario, fault_case, *c.run.controller, nullptr, &*c.setup.config);
  if (!obs.error.empty()) {
    row["status"] = "error";
    row["reason"] = obs.error;
    return;
  }
  const std::uint32_t mid_code = std::uint32_t{1} << (scenario.dac.bits - 1);
  const bool met = hil::fault_case_met(fault_case, obs, mid_code);
  const nlohmann::json j = hil::fault_case_json(fault_case, obs, met);
  row["status"] = "ok";
  if (!met) {
    const bool latched_expected = obs.detected && (obs.fault.reason == fault_case.expected ||
                                                   obs.fault.reason == fault_case.also_accepted);
    row["reason"] = std::string("not met: expected ") + fw::to_string(fault_case.expected) + ", latched " +
                    hil::latched_text(obs) +
                    (latched_expected ? " but the outputs were not safe right after the latching tick" : "");
  }
  for (const auto& [key, value] : j.items())
    if (row.contains(key) && key != "status" && key != "reason") row[key] = value;
}

}  // namespace

const Experiment& faults_experiment() {
  static const Experiment e = [] {
    Experiment x;
    x.name = "faults";
    x.controllers = ControllerUse::choose;
    x.settings = {{"fault_case", SettingType::string, true, nullptr}};
    x.results = {{"ok", "INTEGER"},           {"latched", "TEXT"},        {"axis", "TEXT"},
                 {"injected_s", "REAL"},      {"ticks_to_detect", "INTEGER"}, {"time_to_safe_ms", "REAL"},
                 {"latching_tick", "INTEGER"}, {"fault_tick", "INTEGER"},   {"watchdog_tripped", "INTEGER"},
                 {"deviation_um", "REAL"},    {"missed_ticks", "INTEGER"}, {"late_ticks", "INTEGER"}};
    x.default_metric = "time_to_safe_ms";
    x.check_settings = check_fault_settings;
    x.check_input = any_input;
    x.base_settings = default_base_settings;
    x.run = run_faults_row;
    return x;
  }();
  return e;
}

}  // namespace tnv::campaign
