#pragma once
// What a campaign needs to know about each tnv-hil experiment it runs
// (docs/campaigns.md "Experiments"): its own keys in the campaign file,
// which controllers and [vary] inputs it takes, the result keys of its
// rows (named as the experiment's own JSON names them) and how one run
// is done, through the experiment's library (tools/hil), never a copy.
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "firmware/can/node_settings.hpp"
#include "tools/campaign/run_inputs.hpp"

namespace tnv::campaign {

struct Manifest;
struct ManifestRun;

enum class SettingType { string, number, integer, boolean, integer_list };

// An experiment's own key in the campaign file (e.g. path's "program").
struct SettingKey {
  std::string name;
  SettingType type = SettingType::number;
  bool required = false;
  nlohmann::ordered_json default_value;  // used when the key is absent (not required)
};

struct ResultKey {
  std::string name;      // as the experiment's JSON names it
  std::string sql_type;  // the column's type in campaign.sqlite: REAL, INTEGER or TEXT
};

enum class ControllerUse {
  choose,      // `controllers` required: each sample is run once with each
  rdvsc_only,  // the experiment runs R-DVSC+DDC (`controllers` may only say so)
  none,        // no axis loops (boring's planner): `controllers` is refused
};

struct RunContext {
  const Manifest& manifest;
  const ManifestRun& run;
  const RunSetup& setup;  // the run's scenario and node settings, resolved
};

struct Experiment {
  std::string name;
  ControllerUse controllers = ControllerUse::choose;
  std::vector<SettingKey> settings;
  std::vector<ResultKey> results;
  std::string default_metric;  // what `report` judges unless --metric says otherwise
  // Why the settings (every key present, defaults filled in) cannot be
  // run, "" when they can; `key` names the setting at fault.
  std::string (*check_settings)(const nlohmann::ordered_json& settings, const std::string& program_text,
                                std::string& key) = nullptr;
  // Why a [vary] name (already known to be a scenario key or a writable
  // parameter) is not an input of this experiment; "" when it is.
  std::string (*check_input)(const std::string& name, bool is_parameter) = nullptr;
  // The node settings a run starts from before its varied parameters.
  fw::can::NodeSettings (*base_settings)() = nullptr;
  // One run: sets the row's status, reason and results (they are null
  // until set). May throw; the caller turns that into an "error" row.
  void (*run)(const RunContext& context, nlohmann::ordered_json& row) = nullptr;
};

// nullptr for a name no campaign runs.
const Experiment* find_experiment(std::string_view name);
const std::vector<const Experiment*>& all_experiments();
std::string experiment_names();  // "circle, path, ..." for messages

// The experiments, one file each (experiment_<name>.cpp).
const Experiment& circle_experiment();
const Experiment& path_experiment();
const Experiment& faults_experiment();
const Experiment& homing_experiment();
const Experiment& boring_experiment();
const Experiment& arsc_tick_experiment();

// Shared by the experiments' files.
fw::can::NodeSettings default_base_settings();
std::string any_input(const std::string& name, bool is_parameter);

}  // namespace tnv::campaign
