// The named scenarios every tool knows (scenario_file.hpp).
#include <array>

#include "emulator/scenario_file.hpp"

namespace tnv::emu {

namespace {

Scenario named(std::string_view name) {
  Scenario s;
  s.name = std::string(name);
  return s;
}

// S1 experiment: cutting at 900/1200/1500 rpm -> 30/40/50 Hz with 2 flutes.
Scenario cutting_at(std::string_view name, double spindle_rpm) {
  Scenario s = named(name);
  s.cutting.enabled = true;
  s.cutting.spindle_rpm = spindle_rpm;
  return s;
}

// S2 XY stage: lightly damped 30 Hz / 100 Hz mode on X, for input shaping.
Scenario flexible_x(std::string_view name, double mode_hz) {
  Scenario s = named(name);
  s.plant[0].mode_hz = mode_hz;
  s.plant[0].mode_zeta = 0.02;
  return s;
}

constexpr std::array<std::string_view, 6> kNames{"no-cut", "cut-900", "cut-1200", "cut-1500", "flex-30", "flex-100"};

}  // namespace

std::optional<Scenario> builtin_scenario(std::string_view name) {
  if (name == "no-cut") return named(name);
  if (name == "cut-900") return cutting_at(name, 900.0);
  if (name == "cut-1200") return cutting_at(name, 1200.0);
  if (name == "cut-1500") return cutting_at(name, 1500.0);
  if (name == "flex-30") return flexible_x(name, 30.0);
  if (name == "flex-100") return flexible_x(name, 100.0);
  return std::nullopt;
}

std::vector<std::string> builtin_scenario_names() { return {kNames.begin(), kNames.end()}; }

ScenarioResult resolve_scenario(std::string_view name_or_path) {
  if (auto builtin = builtin_scenario(name_or_path)) return ScenarioResult{std::move(builtin), {}};
  return load_scenario_file(std::string(name_or_path));
}

}  // namespace tnv::emu
