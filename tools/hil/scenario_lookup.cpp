#include "tools/hil/scenario_lookup.hpp"

#include "emulator/scenario_file.hpp"

namespace tnv::hil {

ScenarioLookup lookup_scenario(const std::string& name_or_file) {
  if (auto builtin = emu::builtin_scenario(name_or_file)) return {std::move(builtin), {}};
  emu::ScenarioResult loaded = emu::load_scenario_file(name_or_file);
  if (!loaded.scenario) return {std::nullopt, loaded.error};
  return {std::move(loaded.scenario), {}};
}

}  // namespace tnv::hil
