// tnv-hil best-circle | identify (issue 7): the product's best circle
// configuration (identified on the emulated no-cut table, R-DVSC+DDC gains
// by the design rule of tools/hil/tune_design.hpp, Coulomb friction
// feed-forward) beside the papers' R-DVSC+DDC on the four S1 scenarios,
// seed-averaged like table3; and the identification alone.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "tools/hil/best_circle.hpp"
#include "tools/hil/tune_design.hpp"
#include "tools/hil/tune_identify.hpp"
#include "tools/tnv-hil/cli_support.hpp"
#include "tools/tnv-hil/commands.hpp"
#include "tools/hil/report.hpp"

namespace tnv::cli {

namespace {

struct BestCircleOptions {
  int seeds = 8;
  bool json = false;
  std::string plot_dir;
  double fraction = 1.0;
  std::string gains = "autotune";  // autotune | papers
  std::string ff = "coulomb";      // coulomb | stribeck | off
};

int run_best_circle_command(const BestCircleOptions& o) {
  const auto table3 = resolve_table3_scenarios_or_report();
  if (!table3) return kExitFailure;
  const std::vector<emu::Scenario>& scenarios = *table3;
  // The friction model comes from identifying the no-cut table the way
  // `tnvctl identify` does (the firmware's excitation, the host's fit).
  std::array<hil::AxisDesign, 2> designs{};
  nlohmann::json identified = nlohmann::json::array();
  for (std::size_t i = 0; i < 2; ++i) {
    const hil::AxisIdentification id = hil::identify_axis_on_emulator(scenarios[0], hal::axis_from_index(i));
    designs[i] = hil::design_axis(id);
    if (!designs[i].ok) {
      std::fprintf(stderr, "tnv-hil: best-circle: axis %s: %s\n", i == 0 ? "x" : "y", designs[i].error.c_str());
      return kExitFailure;
    }
    designs[i].friction.fraction = o.fraction;
    // --ff stribeck: the whole identified model (f_s and the assumed v_s) fed forward.
    if (o.ff == "stribeck") designs[i].friction.stiction_mm_s = std::max(id.stiction_mm_s, id.coulomb_mm_s);
    if (o.ff == "off") designs[i].friction.enabled = false;
    identified.push_back({{"identification", hil::identification_json(id)}, {"design", hil::design_json(designs[i])}});
  }
  fw::FirmwareConfig best = hil::apply_designs(fw::default_firmware_config(), designs[0], designs[1]);
  if (o.gains == "papers") {
    best = fw::default_firmware_config();
    for (std::size_t i = 0; i < 2; ++i) best.axis[i].friction = designs[i].friction;
  }
  if (const fw::ConfigError e = fw::validate(best); !e.ok()) {
    std::fprintf(stderr, "tnv-hil: best-circle: %s: %s: %s\n", e.section, e.field, e.reason);
    return kExitBadInput;
  }
  Progress progress("best-circle");
  const auto started = std::chrono::steady_clock::now();
  hil::BestCircleRequest request{scenarios, o.seeds, !o.plot_dir.empty(), std::ref(progress)};
  const std::vector<hil::BestCircleRow> rows = hil::run_best_circle(request, best);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::fprintf(stderr, "[best-circle] %zu runs in %.1f s wall\n", rows.size() * 2 * static_cast<std::size_t>(o.seeds),
               wall_s);
  bool ok = true;
  for (const auto& r : rows) ok = ok && r.error.empty();
  if (o.json) {
    nlohmann::json j = {{"seeds", o.seeds}, {"identified", identified}, {"results", nlohmann::json::array()}};
    for (const auto& r : rows)
      j["results"].push_back(
          {{"scenario", r.scenario}, {"rdvsc", hil::contour_stats_json(r.rdvsc)}, {"best", hil::contour_stats_json(r.best)}, {"error", r.error}});
    std::cout << j.dump(2) << '\n';
  } else {
    char line[256];
    std::snprintf(line, sizeof line, "best circle configuration: R-DVSC+DDC, %s gains, friction feed-forward %s (fraction %.2f), "
                  "seed average over %d seed(s), contour error um\n", o.gains.c_str(), o.ff.c_str(), o.fraction, o.seeds);
    std::string out = line;
    out += "scenario    R-DVSC+DDC max / mean / std        best max / mean / std\n";
    for (const auto& r : rows) {
      std::snprintf(line, sizeof line, "%-10s  %7.4f / %6.4f / %6.4f        %7.4f / %6.4f / %6.4f%s\n",
                    r.scenario.c_str(), r.rdvsc.max_um, r.rdvsc.mean_um, r.rdvsc.std_um, r.best.max_um,
                    r.best.mean_um, r.best.std_um, r.error.empty() ? "" : "  (run failed)");
      out += line;
    }
    std::cout << out;
  }
  if (!o.plot_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(o.plot_dir, ec);
    if (ec) {
      std::fprintf(stderr, "tnv-hil: %s: %s\n", o.plot_dir.c_str(), ec.message().c_str());
      return kExitFailure;
    }
    std::string best_label = o.gains == "autotune" ? "autotuned R-DVSC+DDC" : "papers' R-DVSC+DDC";
    if (o.ff != "off") best_label.append(" + friction FF (").append(o.ff).append(")");
    for (std::size_t s = 0; s < rows.size(); ++s) {
      const hil::BestCircleRow& r = rows[s];
      std::vector<hil::PlotRow> plot_rows{{"R-DVSC+DDC (papers')", r.rdvsc_cell.seed0.stats, &r.rdvsc_cell.seed0.trace},
                                          {best_label, r.best_cell.seed0.stats,
                                           &r.best_cell.seed0.trace}};
      std::string file = "best-circle-";
      file += r.scenario;
      file += ".svg";
      std::string title = "S1 circle, ";
      title += r.scenario;
      title += " (seed 0): before / after, 99.8% of R suppressed";
      ok = write_plot((std::filesystem::path(o.plot_dir) / file).string(), title, scenarios[s].circle.radius_mm,
                      plot_rows) && ok;
    }
  }
  return ok ? kExitOk : kExitFailure;
}

struct IdentifyOptions {
  std::string scenario = "no-cut";
  std::string axis = "x";
  bool json = false;
};

int run_identify_command(const IdentifyOptions& o) {
  const auto scenario = resolve_scenario_or_report(o.scenario);
  if (!scenario) return kExitBadInput;
  std::vector<hal::Axis> axes;
  if (o.axis == "x" || o.axis == "both") axes.push_back(hal::Axis::x);
  if (o.axis == "y" || o.axis == "both") axes.push_back(hal::Axis::y);
  nlohmann::json j = nlohmann::json::array();
  std::string text;
  bool ok = true;
  for (const hal::Axis axis : axes) {
    const hil::AxisIdentification id = hil::identify_axis_on_emulator(*scenario, axis);
    ok = ok && id.ok;
    j.push_back(hil::identification_json(id));
    const std::size_t i = hal::index(axis);
    const emu::AxisPlantParams& truth = scenario->plant[i];
    char line[512];
    if (!id.ok) {
      std::snprintf(line, sizeof line, "axis %s: identification failed: %s\n", i == 0 ? "x" : "y", id.error.c_str());
    } else {
      std::snprintf(line, sizeof line,
                    "axis %s (scenario %s)      identified    scenario's true   error\n"
                    "  tau_s                 %10.6f    %10.6f       %+6.2f %%\n"
                    "  gain K                %10.5f    %10.5f       %+6.2f %%\n"
                    "  coulomb f_c (mm/s)    %10.4f    %10.4f       %+6.2f %%\n"
                    "  stiction f_s (mm/s)   %10.4f    %10.4f       %+6.2f %%\n"
                    "  A = [1 %.7f; 0 %.5f]   B = [%.7f; %.5f]   (1 ms zero-order hold)\n",
                    i == 0 ? "x" : "y", scenario->name.c_str(), id.tau_s, truth.tau_s,
                    100.0 * (id.tau_s / truth.tau_s - 1.0), id.gain, truth.gain, 100.0 * (id.gain / truth.gain - 1.0),
                    id.coulomb_mm_s, truth.coulomb_mm_s, 100.0 * (id.coulomb_mm_s / truth.coulomb_mm_s - 1.0),
                    id.stiction_mm_s, truth.stiction_mm_s, 100.0 * (id.stiction_mm_s / truth.stiction_mm_s - 1.0),
                    id.model.A(0, 1), id.model.A(1, 1), id.model.B(0), id.model.B(1));
    }
    text += line;
  }
  if (o.json)
    std::cout << nlohmann::json({{"scenario", scenario->name}, {"axes", j}}).dump(2) << '\n';
  else
    std::cout << text;
  return ok ? kExitOk : kExitFailure;
}

}  // namespace

void add_best_circle_commands(CLI::App& app, Runner& run) {
  auto id = std::make_shared<IdentifyOptions>();
  CLI::App* id_cmd = app.add_subcommand(
      "identify", "issue 7: open-loop excitation of an axis on the emulated table, fitted tau, K, f_c, f_s");
  id_cmd->add_option("--scenario", id->scenario, "built-in name or TOML file")->capture_default_str();
  id_cmd->add_option("--axis", id->axis, "x | y | both")
      ->check(CLI::IsMember({"x", "y", "both"}))
      ->capture_default_str();
  id_cmd->add_flag("--json", id->json, "print JSON on stdout");
  id_cmd->callback([&run, id] { run = [id] { return run_identify_command(*id); }; });

  auto o = std::make_shared<BestCircleOptions>();
  CLI::App* cmd = app.add_subcommand(
      "best-circle", "autotuned R-DVSC+DDC + friction feed-forward beside the papers' R-DVSC+DDC, 4 scenarios");
  cmd->add_option("--seeds", o->seeds, "average over N encoder offsets / cutting phases")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "print JSON on stdout");
  cmd->add_option("--plot-dir", o->plot_dir, "write one before/after SVG figure per scenario here");
  cmd->add_option("--ff-fraction", o->fraction, "share of the identified friction model fed forward")
      ->check(CLI::Range(0.0, 1.5))
      ->capture_default_str();
  cmd->add_option("--gains", o->gains, "autotune (designed from the identified table) | papers (S1 Tables 1/2)")
      ->check(CLI::IsMember({"autotune", "papers"}))
      ->capture_default_str();
  cmd->add_option("--ff", o->ff, "friction feed-forward: coulomb (the rule) | stribeck (whole model) | off")
      ->check(CLI::IsMember({"coulomb", "stribeck", "off"}))
      ->capture_default_str();
  cmd->callback([&run, o] { run = [o] { return run_best_circle_command(*o); }; });
}

}  // namespace tnv::cli
