#include "tools/campaign/run_inputs.hpp"

#include <map>
#include <mutex>

#include "emulator/scenario_file.hpp"
#include "emulator/scenario_validation.hpp"
#include "tools/campaign/experiment.hpp"
#include "tools/can/param_assignments.hpp"

namespace tnv::campaign {

namespace {

// "run:3:1: plant.x.gain: must be > 0" -> "plant.x.gain: must be > 0".
std::string without_position(const std::string& error) {
  std::size_t at = 0;
  for (int colons = 0; colons < 3; ++colons) {
    at = error.find(':', at);
    if (at == std::string::npos) return error;
    ++at;
  }
  return at < error.size() && error[at] == ' ' ? error.substr(at + 1) : error.substr(at);
}

// The whole-settings check computes loop margins (about 6 ms): without
// parameter inputs every run of an experiment has its base settings,
// checked once per process.
const can_host::NodeAssignmentsResult& checked_base_settings(std::string_view experiment) {
  static std::mutex mutex;
  static std::map<std::string, can_host::NodeAssignmentsResult, std::less<>> cache;
  const std::lock_guard<std::mutex> lock(mutex);
  auto it = cache.find(experiment);
  if (it == cache.end()) {
    const Experiment* e = find_experiment(experiment);
    const fw::can::NodeSettings base = e != nullptr ? e->base_settings() : default_base_settings();
    it = cache.emplace(std::string(experiment), can_host::node_settings_from_assignments({}, base)).first;
  }
  return it->second;
}

}  // namespace

std::string toml_value_text(const nlohmann::ordered_json& value) {
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  if (value.is_number_integer()) return value.dump();
  if (value.is_number()) {
    std::string text = emu::format_number(value.get<double>());
    // A TOML float needs a point or an exponent; "2" would be an integer.
    if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
    return text;
  }
  return value.dump();  // a JSON string is a valid TOML basic string
}

std::string param_value_text(const nlohmann::ordered_json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  if (value.is_number_integer()) return value.dump();
  return emu::format_number(value.get<double>());
}

RunSetup resolve_run_inputs(const emu::Scenario& base, const std::vector<InputName>& names,
                            const nlohmann::ordered_json& values, std::string_view experiment) {
  RunSetup setup;
  std::string overlay;
  std::vector<std::string> assignments;
  for (const InputName& n : names) {
    const auto it = values.find(n.name);
    if (it == values.end()) {
      setup.error = n.name + ": no value";
      setup.bad_input = n.name;
      return setup;
    }
    if (n.is_parameter) {
      assignments.push_back(n.name + "=" + param_value_text(*it));
    } else {
      overlay += n.name + " = " + toml_value_text(*it) + "\n";
    }
  }
  emu::ScenarioResult scenario = emu::apply_scenario_text(base, overlay, "run");
  if (!scenario.scenario) {
    setup.error = without_position(scenario.error);
    setup.unknown_key = scenario.unknown_key;
    for (const InputName& n : names)
      if (!n.is_parameter && setup.error.rfind(n.name + ":", 0) == 0) setup.bad_input = n.name;
    return setup;
  }
  const can_host::NodeAssignmentsResult& base_settings = checked_base_settings(experiment);
  if (!base_settings.settings) {
    setup.error = base_settings.error;
    return setup;
  }
  const can_host::NodeAssignmentsResult config =
      assignments.empty() ? base_settings : can_host::node_settings_from_assignments(assignments, *base_settings.settings);
  if (!config.settings) {
    setup.error = config.error;
    for (const InputName& n : names)
      if (n.is_parameter && config.error.find(n.name) != std::string::npos) setup.bad_input = n.name;
    return setup;
  }
  setup.scenario = std::move(scenario.scenario);
  setup.config = config.settings->firmware;
  setup.bore = config.settings->bore;
  return setup;
}

}  // namespace tnv::campaign
