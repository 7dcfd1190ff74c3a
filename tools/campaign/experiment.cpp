#include "tools/campaign/experiment.hpp"

namespace tnv::campaign {

const std::vector<const Experiment*>& all_experiments() {
  static const std::vector<const Experiment*> all = {&circle_experiment(), &path_experiment(),
                                                     &faults_experiment(), &homing_experiment(),
                                                     &boring_experiment(), &arsc_tick_experiment()};
  return all;
}

const Experiment* find_experiment(std::string_view name) {
  for (const Experiment* e : all_experiments())
    if (e->name == name) return e;
  return nullptr;
}

std::string experiment_names() {
  std::string names;
  for (const Experiment* e : all_experiments()) names += (names.empty() ? "\"" : ", \"") + e->name + "\"";
  return names;
}

fw::can::NodeSettings default_base_settings() { return fw::can::default_node_settings(); }

std::string any_input(const std::string&, bool) { return {}; }

}  // namespace tnv::campaign
