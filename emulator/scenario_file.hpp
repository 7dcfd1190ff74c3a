#pragma once
// Scenarios from TOML files (toml++) and the built-in set. Every key is
// optional; defaults come from scenario.hpp. Errors are one line:
//   "scen.toml:7:1: plant.x.tau_s: must be > 0 and finite (got -1)"
// and on error no Scenario is returned (nothing half-applied).
//
// The keys, their ranges and defaults: docs/scenarios.md; their table
// (section, name, member, range) is scenario_keys.cpp, read here and
// checked by scenario_validation.cpp. Errors name "fault[i].key" for the i-th
// [[fault]] (from 0). Integers are accepted where numbers are expected,
// not the other way round.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "emulator/scenario.hpp"

namespace tnv::emu {

struct ScenarioResult {
  std::optional<Scenario> scenario;
  std::string error;  // empty on success
  bool unknown_key = false;  // the error is a key or section the format does not have
};

// A scenario is a few kB of TOML; past kMaxScenarioBytes (1 MiB) it is refused,
// as is anything but a regular file (text_file.hpp).
inline constexpr std::size_t kMaxScenarioBytes = std::size_t{1} << 20;
ScenarioResult load_scenario_file(const std::string& path);
ScenarioResult parse_scenario_text(std::string_view text, std::string_view source_name);
// `base` with the keys of `overlay` (this format, e.g. "plant.x.gain = 1.1")
// applied on top, then the whole scenario checked as a file is: a campaign
// run's scenario (tools/campaign).
ScenarioResult apply_scenario_text(const Scenario& base, std::string_view overlay, std::string_view source_name);

// Built-ins: no-cut, cut-900, cut-1200, cut-1500, flex-30, flex-100,
// bench-no-cut, bench-cut-1200.
std::optional<Scenario> builtin_scenario(std::string_view name);
std::vector<std::string> builtin_scenario_names();

// A built-in name if it is one, else a file path.
ScenarioResult resolve_scenario(std::string_view name_or_path);

}  // namespace tnv::emu
