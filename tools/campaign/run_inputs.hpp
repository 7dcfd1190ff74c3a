#pragma once
// A run's machine and firmware from the base scenario and the run's
// values of the varied inputs: scenario keys through the scenario loader
// (emu::apply_scenario_text), parameters through the parameter table
// (can_host::node_settings_from_assignments, on top of the experiment's
// own base settings: homing's, the defaults for the rest). Plan checks every run
// with this before writing a manifest; runs and replays build with it.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "emulator/scenario.hpp"
#include "firmware/adaptive/boring/boring_station.hpp"
#include "firmware/tick/firmware_config.hpp"

namespace tnv::campaign {

struct InputName {
  std::string name;
  bool is_parameter = false;
};

struct RunSetup {
  std::optional<emu::Scenario> scenario;
  std::optional<fw::FirmwareConfig> config;
  fw::BoringStationSettings bore{};  // the boring planner's settings (bore.* parameters)
  std::string error;      // one line, without a file position
  std::string bad_input;  // the input it names, when it names one
  bool unknown_key = false;  // a scenario key the scenario format does not have
};

// `values`: an object, name -> number, boolean or string. `experiment`:
// whose base settings the parameters apply to (experiment.hpp).
RunSetup resolve_run_inputs(const emu::Scenario& base, const std::vector<InputName>& names,
                            const nlohmann::ordered_json& values, std::string_view experiment = "circle");

// A value as a TOML value ("1.5", "true", "\"pid\"") and as parameter text.
std::string toml_value_text(const nlohmann::ordered_json& value);
std::string param_value_text(const nlohmann::ordered_json& value);

}  // namespace tnv::campaign
