// tnv-hil homing: the firmware's homing cycle on the emulated table over
// seeded power-up positions and encoder phases; the home error against the
// machine's truth (motor side, tools/hil/homing_run.hpp).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <string>
#include <nlohmann/json.hpp>

#include "hal/axis.hpp"
#include "tools/hil/homing_json.hpp"
#include "tools/hil/homing_run.hpp"
#include "tools/tnv-hil/cli_support.hpp"
#include "tools/tnv-hil/commands.hpp"

namespace tnv::cli {

namespace {

// The goal: home within 0.5 um (one count is 0.417 um).
constexpr double kHomeErrorGoalUm = 0.5;

struct HomingCliOptions {
  std::uint32_t seeds = 10;
  bool json = false;
  std::string scenario;  // "" = the reference table
};

int run_homing_command(const HomingCliOptions& o) {
  emu::Scenario scenario = hil::homing_scenario();
  if (!o.scenario.empty()) {
    const std::optional<emu::Scenario> table = resolve_scenario_or_report(o.scenario);
    if (!table) return kExitBadInput;
    scenario = hil::with_homing_board(*table);
  }
  const fw::FirmwareConfig config = hil::homing_firmware_config();
  const hil::HomingSummary sum = hil::run_homing(scenario, config, o.seeds);
  const bool met = sum.all_homed && sum.home_error_um_max <= kHomeErrorGoalUm;
  if (o.json) {
    nlohmann::json seeds = nlohmann::json::array();
    for (const hil::HomingSeedResult& r : sum.seeds) {
      seeds.push_back(hil::homing_seed_json(r));
    }
    nlohmann::json out = {{"seeds", o.seeds},
                                {"scenario", scenario.name},
                                {"reference", "motor side: firmware position - homing.position_mm vs true motor "
                                              "position - the index mark past the switch; home error without the "
                                              "present reading's rounding to a count, reading error with it"},
                                {"home_error_um_max", sum.home_error_um_max},
                                {"home_error_spread_um", sum.home_error_spread_um},
                                {"reading_error_um_max", sum.reading_error_um_max},
                                {"goal_um", kHomeErrorGoalUm},
                                {"time_s_max", sum.time_s_max},
                                {"all_homed", sum.all_homed},
                                {"runs", seeds}};
    note_io_work_unmetered(out, scenario);
    std::cout << out.dump(2) << "\n";
  } else {
    std::string order;  // "x then y"
    for (const hal::Axis a : hal::kHomingOrder) order += (order.empty() ? "" : " then ") + std::string(hal::axis_label(a));
    std::printf("homing on %s: %u seeds (power-up within +-20 mm, any count offset and phase), %s, %s\n",
                scenario.name.c_str(), o.seeds, hal::kAxisCount == 2 ? "both axes" : "every axis", order.c_str());
    std::printf("%5s", "seed");
    for (const hal::Axis a : hal::kAxes) std::printf(" %9s", hil::axis_key("*0_mm", a).c_str());
    for (const hal::Axis a : hal::kAxes) std::printf(" %10s", hil::axis_key("cnt_*", a).c_str());
    std::printf(" %7s", "homed");
    for (const hal::Axis a : hal::kAxes) std::printf(" %10s", hil::axis_key("err_*_um", a).c_str());
    std::printf(" %7s\n", "time_s");
    for (const hil::HomingSeedResult& r : sum.seeds) {
      std::printf("%5u", r.seed);
      for (const double v : r.power_up_offset_mm) std::printf(" %9.3f", v);
      for (const double v : r.offset_counts) std::printf(" %10.3f", v);
      std::printf(" %7s", r.homed ? "yes" : "NO");
      for (const double v : r.home_error_um) std::printf(" %10.4f", v);
      std::printf(" %7.2f%s%s\n", r.time_s, r.failure.empty() ? "" : "  ", r.failure.c_str());
    }
    std::printf("home_error_um_max %.4f (goal %.1f, motor side), spread %.4f um, reading_error_um_max %.4f, "
                "time_s_max %.2f\n",
                sum.home_error_um_max, kHomeErrorGoalUm, sum.home_error_spread_um, sum.reading_error_um_max,
                sum.time_s_max);
  }
  if (!sum.all_homed) std::fprintf(stderr, "tnv-hil homing: a homing failed\n");
  else if (!met) std::fprintf(stderr, "tnv-hil homing: home error above %.1f um\n", kHomeErrorGoalUm);
  return met ? kExitOk : kExitFailure;
}

}  // namespace

void add_homing_commands(CLI::App& app, Runner& run) {
  auto o = std::make_shared<HomingCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "homing", "homing cycle of both axes over seeded power-up positions and encoder phases; home error (motor side)");
  cmd->add_option("--seeds", o->seeds, "power-ups to home from")->capture_default_str()->check(CLI::Range(1, 10000));
  cmd->add_flag("--json", o->json, "JSON on stdout");
  cmd->add_option("--scenario", o->scenario,
                  "the table (built-in name or TOML file); without home switches of its own it gets the reference "
                  "board's (default: the reference table)");
  cmd->callback([o, &run]() { run = [o]() { return run_homing_command(*o); }; });
}

}  // namespace tnv::cli
