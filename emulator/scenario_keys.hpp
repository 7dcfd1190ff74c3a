#pragma once
// Every key of a scenario file, once: its section, its name, the Scenario
// member it sets and its range on its own (scenario_key_rule.hpp). The
// reader (scenario_file.cpp) reads the keys from it and the validation
// (scenario_validation.cpp) checks their ranges from it; rules between keys
// stay code there. Per-axis keys come from the axis list (hal/axis.hpp):
// [plant.<axis>], [encoder] offset_counts_<axis>, [board] <field>_<axis>.
// A new key: its member and default (scenario.hpp), one row here
// (scenario_keys.cpp), the physics that uses it, and its line in
// docs/scenarios.md (tests/emulator/scenario_keys_test.cpp checks the table
// against the Scenario and the doc).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "emulator/scenario.hpp"
#include "emulator/scenario_key_rule.hpp"

namespace tnv::emu {

using FieldTarget = std::variant<double*, int*, bool*, std::uint32_t*, std::string*>;

struct ScenarioKey {
  std::string section;  // "plant.x", "cutting"; empty for a top-level key ("name")
  std::string name;     // "tau_s"
  std::function<FieldTarget(Scenario&)> target;  // the member it sets
  // Numbers' rules; booleans, strings and the uint32 keys have none (their type is their range).
  KeyRule rule;

  std::string path() const { return section.empty() ? name : section + "." + name; }  // "plant.x.tau_s"
};

// The table, in the order the validation checks it.
const std::vector<ScenarioKey>& scenario_keys();

// The row for `name` in `section`, none if the format has no such key.
const ScenarioKey* find_scenario_key(std::string_view section, std::string_view name);

// Whether `path` is a section of the table or holds sections ("plant" holds "plant.x").
bool is_scenario_section(std::string_view path);

// A number key's value in `scenario` (double, int or uint32), none for the others.
std::optional<double> scenario_key_number(const ScenarioKey& key, const Scenario& scenario);

}  // namespace tnv::emu
