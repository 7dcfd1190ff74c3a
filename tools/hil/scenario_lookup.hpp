#pragma once
// NAME|FILE resolution for --scenario: a built-in name first, else a TOML file.
#include <optional>
#include <string>

#include "emulator/scenario.hpp"

namespace tnv::hil {

struct ScenarioLookup {
  std::optional<emu::Scenario> scenario;
  std::string error;  // one line: file:line:col: key: reason
};

ScenarioLookup lookup_scenario(const std::string& name_or_file);

}  // namespace tnv::hil
