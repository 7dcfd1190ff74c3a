#pragma once
// The ranges a Scenario must respect before a Machine is built from it;
// shared by the TOML loader and by code that builds scenarios directly.
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "emulator/scenario.hpp"

namespace tnv::emu {

struct ScenarioViolation {
  std::string key;      // dotted TOML key, e.g. "plant.x.tau_s"
  std::string message;  // e.g. "must be > 0 and finite (got -1)"
};

// First rule the scenario breaks, if any. `given` tells which keys a file
// set explicitly, so a rule between two keys (stiction >= coulomb) is
// reported at a key the user wrote.
std::optional<ScenarioViolation> find_scenario_violation(
    const Scenario& scenario, const std::function<bool(std::string_view key)>& given = {});

// "" if valid, else "key: message".
std::string validate_scenario(const Scenario& scenario);

// Shortest round-trip text of a number ("-1", "0.005", "nan").
std::string format_number(double value);

}  // namespace tnv::emu
