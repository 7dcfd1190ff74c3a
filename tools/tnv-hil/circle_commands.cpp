// tnv-hil circle | table3 | plant-check: the S1 experiments.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "firmware/tick/firmware_config.hpp"
#include "tools/cli/output_path.hpp"
#include "tools/hil/plot_data.hpp"
#include "tools/hil/plant_check.hpp"
#include "tools/hil/report.hpp"
#include "tools/hil/seed_sweep.hpp"
#include "tools/tnv-hil/cli_support.hpp"
#include "tools/tnv-hil/commands.hpp"

namespace tnv::cli {

namespace {

std::string trace_csv(const std::vector<hil::TraceSample>& trace) {
  std::string out = "t_s,x_ref_mm,y_ref_mm,x_mm,y_mm,contour_um,u_x_mm_s,u_y_mm_s,s_x,s_y,d_hat_x_mm_s,d_hat_y_mm_s\n";
  char buf[320];
  for (const hil::TraceSample& t : trace) {
    std::snprintf(buf, sizeof buf, "%.3f,%.9f,%.9f,%.9f,%.9f,%.5f,%.5f,%.5f,%.6g,%.6g,%.6g,%.6g\n", t.t_s,
                  t.reference_mm[0], t.reference_mm[1], t.position_mm[0], t.position_mm[1], t.contour_um,
                  t.command_mm_s[0], t.command_mm_s[1], t.s[0], t.s[1], t.d_hat_mm_s[0], t.d_hat_mm_s[1]);
    out += buf;
  }
  return out;
}

struct CircleOptions {
  std::string controller = "rdvsc";
  std::string scenario = "no-cut";
  int seeds = 1;
  bool json = false;
  std::string plot;
  std::string csv;
  std::optional<double> gamma;  // both axes' sliding.gamma; unset: the papers'
  std::vector<std::string> sets;  // NAME=VALUE firmware parameters
  std::vector<std::string> params_files;  // parameter files' [params], before the sets
};

int run_circle_command(const CircleOptions& o) {
  const auto kind = controller_or_report(o.controller);
  const auto scenario = resolve_scenario_or_report(o.scenario);
  if (!kind || !scenario) return kExitBadInput;
  const std::optional<fw::FirmwareConfig> configured = firmware_config_or_report(o.params_files, o.sets);
  if (!configured) return kExitBadInput;
  fw::FirmwareConfig config = *configured;
  for (auto& axis : config.axis) axis.sliding.gamma = o.gamma.value_or(axis.sliding.gamma);
  if (const fw::ConfigError e = fw::validate(config); !e.ok()) {
    std::fprintf(stderr, "tnv-hil: --gamma: %s: %s: %s\n", e.section, e.field, e.reason);
    return kExitBadInput;
  }
  Progress progress("circle");
  hil::SweepRequest request{{*scenario}, {*kind}, o.seeds, !o.plot.empty() || !o.csv.empty(), 0, {}};
  if (o.seeds > 1) request.progress = std::ref(progress);
  const std::vector<hil::SweepCell> cells = hil::run_sweep(request, config);
  const hil::SweepCell& cell = cells.front();
  if (o.json) {
    nlohmann::json j = {{"results", hil::results_json(cells, o.seeds)}, {"pid_gains", hil::pid_gains_json(config)}};
    note_io_work_unmetered(j, *scenario);
    std::cout << j.dump(2) << '\n';
  } else {
    std::cout << hil::circle_text(cell, o.seeds);
    if (*kind == fw::ControllerKind::pid) std::cout << hil::pid_gains_text(config);
  }
  bool ok = cell.error.empty();
  if (!o.plot.empty()) {
    const std::string title = "S1 circle, " + cell.scenario + ", " + fw::to_string(cell.controller) + " (seed 0)";
    ok = write_plot(o.plot, title, scenario->circle.radius_mm,
                    {{fw::to_string(cell.controller), cell.seed0.stats, &cell.seed0.trace}}) && ok;
  }
  if (!o.csv.empty()) ok = write_text(o.csv, trace_csv(cell.seed0.trace)) && ok;
  if (!cell.error.empty()) std::fprintf(stderr, "tnv-hil: run failed: %s\n", cell.error.c_str());
  return ok ? kExitOk : kExitFailure;
}

struct Table3Options {
  int seeds = 8;
  bool json = false;
  std::string plot_dir;
};

int run_table3_command(const Table3Options& o) {
  const auto table3 = resolve_table3_scenarios_or_report();
  if (!table3) return kExitFailure;
  const std::vector<emu::Scenario>& scenarios = *table3;
  const fw::FirmwareConfig config = fw::default_firmware_config();
  Progress progress("table3");
  const auto started = std::chrono::steady_clock::now();
  hil::SweepRequest request{scenarios,
                            {fw::ControllerKind::pid, fw::ControllerKind::dvsc, fw::ControllerKind::rdvsc},
                            o.seeds,
                            !o.plot_dir.empty(),
                            0,
                            std::ref(progress)};
  const std::vector<hil::SweepCell> cells = hil::run_sweep(request, config);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::fprintf(stderr, "[table3] %zu runs in %.1f s wall\n", cells.size() * static_cast<std::size_t>(o.seeds), wall_s);

  if (o.json) {
    nlohmann::json j = {{"results", hil::results_json(cells, o.seeds)},
                        {"ratios", hil::table3_ratios_json(cells)},
                        {"pid_gains", hil::pid_gains_json(config)}};
    std::cout << j.dump(2) << '\n';
  } else {
    std::cout << hil::table3_text(cells, o.seeds, config);
  }
  bool ok = true;
  for (const auto& c : cells) ok = ok && c.error.empty();
  if (!o.plot_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(o.plot_dir, ec);
    if (ec) {
      std::fprintf(stderr, "tnv-hil: %s: %s\n", o.plot_dir.c_str(), ec.message().c_str());
      return kExitFailure;
    }
    for (std::size_t s = 0; s < scenarios.size(); ++s) {
      std::vector<hil::PlotRow> rows;
      for (std::size_t c = 0; c < 3; ++c) {
        const hil::SweepCell& cell = cells[s * 3 + c];
        rows.push_back({fw::to_string(cell.controller), cell.seed0.stats, &cell.seed0.trace});
      }
      const std::string path = (std::filesystem::path(o.plot_dir) / ("circle-" + scenarios[s].name + ".svg")).string();
      ok = write_plot(path, "S1 circle, " + scenarios[s].name + " (seed 0): polar plot with 99.8% of R suppressed",
                      scenarios[s].circle.radius_mm, rows) && ok;
    }
  }
  return ok ? kExitOk : kExitFailure;
}

struct PlantCheckOptions {
  std::string scenario = "no-cut";
  bool json = false;
};

int run_plant_check_command(const PlantCheckOptions& o) {
  const auto scenario = resolve_scenario_or_report(o.scenario);
  if (!scenario) return kExitBadInput;
  const auto axes = hil::plant_check(*scenario);
  if (o.json)
    std::cout << hil::plant_check_json(axes).dump(2) << '\n';
  else
    std::cout << hil::plant_check_text(axes);
  return kExitOk;
}

}  // namespace

void add_circle_commands(CLI::App& app, Runner& run) {
  auto circle = std::make_shared<CircleOptions>();
  CLI::App* circle_cmd = app.add_subcommand("circle", "one S1 circle (radius 6 mm, 2 mm/s) and its contour error");
  circle_cmd->add_option("--controller", circle->controller, "pid | dvsc | rdvsc")
      ->check(CLI::IsMember({"pid", "dvsc", "rdvsc"}))
      ->capture_default_str();
  circle_cmd->add_option("--scenario", circle->scenario, "built-in name (no-cut, cut-900, cut-1200, cut-1500) or TOML file")
      ->capture_default_str();
  circle_cmd->add_option("--seeds", circle->seeds, "average over N encoder offsets / cutting phases")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  circle_cmd->add_flag("--json", circle->json, "print JSON on stdout");
  circle_cmd->add_option("--plot", circle->plot, "write the polar + contour-error plot (.svg, .png or .pdf)")->check(tnv::cli::PlotFile());
  circle_cmd->add_option("--csv", circle->csv, "write the seed-0 trace (CSV)")->check(tnv::cli::OutputFile());
  circle_cmd->add_option("--gamma", circle->gamma, "R-DVSC gamma of both axes (default: the papers', S1 Table 2)");
  circle_cmd->add_option("--set", circle->sets,
                         "NAME=VALUE: a firmware parameter as on the node, e.g. x.screw.backlash_um=10 (repeatable)");
  circle_cmd->add_option("--params", circle->params_files,
                         "a parameter file (tnvctl params export, tnv-hil screw-fit --params-out) applied before --set (repeatable)")
      ->check(CLI::ExistingFile);
  circle_cmd->callback([&run, circle] { run = [circle] { return run_circle_command(*circle); }; });

  auto table3 = std::make_shared<Table3Options>();
  CLI::App* table3_cmd = app.add_subcommand("table3", "S1 Table 3: 4 scenarios x 3 controllers beside the paper");
  table3_cmd->add_option("--seeds", table3->seeds, "average over N encoder offsets / cutting phases")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  table3_cmd->add_flag("--json", table3->json, "print JSON on stdout");
  table3_cmd->add_option("--plot-dir", table3->plot_dir, "write one SVG figure (and its .plot.json data) per scenario here")->check(tnv::cli::OutputDir());
  table3_cmd->callback([&run, table3] { run = [table3] { return run_table3_command(*table3); }; });

  auto plant = std::make_shared<PlantCheckOptions>();
  CLI::App* plant_cmd = app.add_subcommand("plant-check", "identify the emulated axes' 1 ms A, B beside exact and paper");
  plant_cmd->add_option("--scenario", plant->scenario, "built-in name or TOML file")->capture_default_str();
  plant_cmd->add_flag("--json", plant->json, "print JSON on stdout");
  plant_cmd->callback([&run, plant] { run = [plant] { return run_plant_check_command(*plant); }; });
}

}  // namespace tnv::cli
