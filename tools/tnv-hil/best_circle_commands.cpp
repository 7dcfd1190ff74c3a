// tnv-hil best-circle | identify (issue 7): the product's best circle
// configuration (identified on the emulated no-cut table, R-DVSC+DDC gains
// by the design rule of tools/tune/axis_design.hpp, Coulomb friction
// feed-forward, speed observer with the identified friction) beside the
// papers' R-DVSC+DDC on the four S1 scenarios, seed-averaged like table3;
// with --scenario, the same made from and run on other tables (beside the
// design with its observer off); and the identification alone.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>

#include "tools/can/tune_json.hpp"
#include "tools/cli/output_path.hpp"
#include "tools/hil/best_circle.hpp"
#include "tools/hil/report.hpp"
#include "tools/hil/tune_identify.hpp"
#include "tools/tnv-hil/cli_support.hpp"
#include "tools/tnv-hil/commands.hpp"

namespace tnv::cli {

namespace {

struct BestCircleOptions {
  int seeds = 8;
  bool json = false;
  std::string plot_dir;
  double fraction = 1.0;
  std::string gains = "autotune";  // autotune | papers
  std::string ff = "coulomb";      // coulomb | stribeck | off
  std::string observer = "speed";  // speed | position | off (speed_observer.hpp)
  double observer_sigma_v_mm_s = tune::kObserverSpeedNoise_mm_s;
  double observer_sigma_d_mm_s = tune::kObserverDisturbanceNoise_mm_s;
  std::string observer_friction = "on";  // on: the identified f_c / K in the observer's model | off
  std::vector<std::string> tables;       // --scenario: run on these tables instead of the four S1 scenarios
};

hil::BestConfigChoice best_choice_from(const BestCircleOptions& o) {
  hil::BestConfigChoice c;
  c.gains = o.gains == "papers" ? hil::BestGains::papers : hil::BestGains::autotune;
  c.ff = o.ff == "stribeck" ? hil::BestFeedForward::stribeck
         : o.ff == "off"    ? hil::BestFeedForward::off
                            : hil::BestFeedForward::coulomb;
  c.ff_fraction = o.fraction;
  c.observer = o.observer == "position" ? hil::BestObserverUse::position
               : o.observer == "off"    ? hil::BestObserverUse::off
                                        : hil::BestObserverUse::speed;
  c.observer_sigma_v_mm_s = o.observer_sigma_v_mm_s;
  c.observer_sigma_d_mm_s = o.observer_sigma_d_mm_s;
  c.observer_friction = o.observer_friction != "off";
  return c;
}

// Identify `table`, design; prints the one-line error and gives the exit code when that fails.
std::optional<hil::BestConfigDesign> best_design_or_report(const emu::Scenario& table, const BestCircleOptions& o,
                                                           int& exit_code) {
  hil::BestConfigDesign d = hil::design_best_config(table, best_choice_from(o));
  if (d.ok) return d;
  std::fprintf(stderr, "tnv-hil: best-circle: %s\n", d.error.c_str());
  exit_code = d.bad_input ? kExitBadInput : kExitFailure;
  return std::nullopt;
}

nlohmann::json best_identified_json(const hil::BestConfigDesign& d) {
  nlohmann::json identified = nlohmann::json::array();
  for (std::size_t i = 0; i < 2; ++i)
    identified.push_back(
        {{"identification", can_host::identification_json(d.identified[i])}, {"design", can_host::design_json(d.designs[i])}});
  return identified;
}

std::string best_label_for(const BestCircleOptions& o, bool with_observer) {
  std::string best_label = o.gains == "autotune" ? "autotuned R-DVSC+DDC" : "papers' R-DVSC+DDC";
  if (o.ff != "off") best_label.append(" + friction FF (").append(o.ff).append(")");
  if (with_observer) best_label.append(" + observer");
  return best_label;
}

bool best_plot_dir_made(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) std::fprintf(stderr, "tnv-hil: %s: %s\n", dir.c_str(), ec.message().c_str());
  return !ec;
}

// --scenario: each named table identified, designed for, and run on (section
// "On tables it was not tuned on" of docs/autotune.md).
int run_best_circle_on_tables(const BestCircleOptions& o) {
  std::vector<emu::Scenario> tables;
  for (const std::string& name : o.tables) {
    auto table = resolve_scenario_or_report(name);
    if (!table) return kExitBadInput;
    tables.push_back(std::move(*table));
  }
  std::vector<hil::BestConfigDesign> designs;
  for (const emu::Scenario& table : tables) {
    int exit_code = kExitFailure;
    auto d = best_design_or_report(table, o, exit_code);
    if (!d) return exit_code;
    designs.push_back(std::move(*d));
  }
  Progress progress("best-circle");
  const std::size_t per_table = 3 * static_cast<std::size_t>(o.seeds);
  const std::size_t total = per_table * tables.size();
  const auto started = std::chrono::steady_clock::now();
  std::vector<hil::TableCheckRow> rows;
  for (std::size_t t = 0; t < tables.size(); ++t) {
    hil::TableCheckRequest request{tables[t], o.seeds, !o.plot_dir.empty(),
                                   [&progress, t, per_table, total](std::size_t done, std::size_t) {
                                     progress(t * per_table + done, total);
                                   }};
    rows.push_back(hil::run_table_check(request, designs[t].config));
  }
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::fprintf(stderr, "[best-circle] %zu runs in %.1f s wall\n", total, wall_s);
  bool ok = true;
  for (const auto& r : rows) ok = ok && r.error.empty();
  if (o.json) {
    nlohmann::json j = {{"seeds", o.seeds}, {"tables", nlohmann::json::array()}};
    for (std::size_t t = 0; t < rows.size(); ++t) {
      const hil::TableCheckRow& r = rows[t];
      j["tables"].push_back({{"scenario", r.scenario},
                             {"identified", best_identified_json(designs[t])},
                             {"rdvsc", hil::contour_stats_json(r.rdvsc)},
                             {"best", hil::contour_stats_json(r.best)},
                             {"best_observer_off", hil::contour_stats_json(r.observer_off)},
                             {"error", r.error}});
    }
    std::cout << j.dump(2) << '\n';
  } else {
    char line[320];
    std::snprintf(line, sizeof line,
                  "best circle configuration designed on each table itself: R-DVSC+DDC, %s gains, friction "
                  "feed-forward %s (fraction %.2f), observer %s; seed average over %d seed(s), contour error um\n",
                  o.gains.c_str(), o.ff.c_str(), o.fraction, o.observer.c_str(), o.seeds);
    std::string out = line;
    out += "table         R-DVSC+DDC (papers')         best                         best, observer off\n";
    out += "              max / mean / std             max / mean / std             max / mean / std\n";
    for (std::size_t t = 0; t < rows.size(); ++t) {
      const hil::TableCheckRow& r = rows[t];
      std::snprintf(line, sizeof line, "%-12s  %7.4f / %6.4f / %6.4f   %7.4f / %6.4f / %6.4f   %7.4f / %6.4f / %6.4f\n",
                    r.scenario.c_str(), r.rdvsc.max_um, r.rdvsc.mean_um, r.rdvsc.std_um, r.best.max_um,
                    r.best.mean_um, r.best.std_um, r.observer_off.max_um, r.observer_off.mean_um,
                    r.observer_off.std_um);
      out += line;
      for (std::size_t i = 0; i < 2; ++i) {
        const tune::AxisIdentification& id = designs[t].identified[i];
        std::snprintf(line, sizeof line,
                      "  identified %s: tau %.3f ms, K %.5f, f_c %.4f mm/s, f_s %.4f mm/s (true %.3f ms, %.5f, %.4f, "
                      "%.4f)\n",
                      hal::kAxisNames[i], 1e3 * id.tau_s, id.gain, id.coulomb_mm_s, id.stiction_mm_s,
                      1e3 * tables[t].plant[i].tau_s, tables[t].plant[i].gain, tables[t].plant[i].coulomb_mm_s,
                      tables[t].plant[i].stiction_mm_s);
        out += line;
      }
      if (!r.error.empty()) out.append("  run failed: ").append(r.error).append("\n");
    }
    std::cout << out;
  }
  if (!o.plot_dir.empty()) {
    if (!best_plot_dir_made(o.plot_dir)) return kExitFailure;
    // Short labels: three rows share the figure's width.
    std::string off_label = o.gains == "autotune" ? "autotuned" : "papers' gains";
    if (o.ff != "off") off_label.append(" + FF (").append(o.ff).append(")");
    std::string best_label = off_label;
    best_label.append(o.observer == "off" ? ", observer off" : " + observer");
    off_label.append(", observer off");
    for (std::size_t t = 0; t < rows.size(); ++t) {
      const hil::TableCheckRow& r = rows[t];
      std::vector<hil::PlotRow> plot_rows{
          {"R-DVSC+DDC (papers')", r.rdvsc_cell.seed0.stats, &r.rdvsc_cell.seed0.trace},
          {best_label, r.best_cell.seed0.stats, &r.best_cell.seed0.trace},
          {off_label, r.observer_off_cell.seed0.stats, &r.observer_off_cell.seed0.trace}};
      std::string file = "best-circle-table-";
      file += r.scenario;
      file += ".svg";
      std::string title = "S1 circle on table ";
      title += r.scenario;
      title += " (seed 0), designed from its own identification";
      ok = write_plot((std::filesystem::path(o.plot_dir) / file).string(), title, tables[t].circle.radius_mm,
                      plot_rows) && ok;
    }
  }
  return ok ? kExitOk : kExitFailure;
}

int run_best_circle_command(const BestCircleOptions& o) {
  if (!o.tables.empty()) return run_best_circle_on_tables(o);
  const auto table3 = resolve_table3_scenarios_or_report();
  if (!table3) return kExitFailure;
  const std::vector<emu::Scenario>& scenarios = *table3;
  // The friction model comes from identifying the no-cut table the way
  // `tnvctl identify` does (the firmware's excitation, the host's fit).
  int exit_code = kExitFailure;
  const auto design = best_design_or_report(scenarios[0], o, exit_code);
  if (!design) return exit_code;
  const nlohmann::json identified = best_identified_json(*design);
  const fw::FirmwareConfig& best = design->config;
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
                  "observer %s, seed average over %d seed(s), contour error um\n", o.gains.c_str(), o.ff.c_str(), o.fraction,
                  o.observer.c_str(), o.seeds);
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
    if (!best_plot_dir_made(o.plot_dir)) return kExitFailure;
    const std::string best_label = best_label_for(o, o.observer != "off");
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
  for (const hal::Axis a : hal::kAxes)
    if (o.axis == hal::axis_label(a) || o.axis == "both") axes.push_back(a);
  nlohmann::json j = nlohmann::json::array();
  std::string text;
  bool ok = true;
  for (const hal::Axis axis : axes) {
    const tune::AxisIdentification id = hil::identify_axis_on_emulator(*scenario, axis);
    ok = ok && id.ok;
    j.push_back(can_host::identification_json(id));
    const std::size_t i = hal::index(axis);
    const emu::AxisPlantParams& truth = scenario->plant[i];
    char line[512];
    if (!id.ok) {
      std::snprintf(line, sizeof line, "axis %s: identification failed: %s\n", hal::kAxisNames[i], id.error.c_str());
    } else {
      std::snprintf(line, sizeof line,
                    "axis %s (scenario %s)      identified    scenario's true   error\n"
                    "  tau_s                 %10.6f    %10.6f       %+6.2f %%\n"
                    "  gain K                %10.5f    %10.5f       %+6.2f %%\n"
                    "  coulomb f_c (mm/s)    %10.4f    %10.4f       %+6.2f %%\n"
                    "  stiction f_s (mm/s)   %10.4f    %10.4f       %+6.2f %%\n"
                    "  A = [1 %.7f; 0 %.5f]   B = [%.7f; %.5f]   (1 ms zero-order hold)\n",
                    hal::kAxisNames[i], scenario->name.c_str(), id.tau_s, truth.tau_s,
                    100.0 * (id.tau_s / truth.tau_s - 1.0), id.gain, truth.gain, 100.0 * (id.gain / truth.gain - 1.0),
                    id.coulomb_mm_s, truth.coulomb_mm_s, 100.0 * (id.coulomb_mm_s / truth.coulomb_mm_s - 1.0),
                    id.stiction_mm_s, truth.stiction_mm_s, 100.0 * (id.stiction_mm_s / truth.stiction_mm_s - 1.0),
                    id.model.A(0, 1), id.model.A(1, 1), id.model.B(0), id.model.B(1));
    }
    text += line;
    if (id.ok) text += hil::mode_fit_text(id.mode_fit, truth.mode_hz, truth.mode_zeta);
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
      "best-circle",
      "autotuned R-DVSC+DDC + friction feed-forward + speed observer beside the papers' R-DVSC+DDC, 4 scenarios");
  cmd->add_option("--seeds", o->seeds, "average over N encoder offsets / cutting phases")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "print JSON on stdout");
  cmd->add_option("--plot-dir", o->plot_dir, "write one before/after SVG figure (and its .plot.json data) per scenario here")->check(tnv::cli::OutputDir());
  cmd->add_option("--ff-fraction", o->fraction, "share of the identified friction model fed forward")
      ->check(CLI::Range(0.0, 1.5))
      ->capture_default_str();
  cmd->add_option("--gains", o->gains, "autotune (designed from the identified table) | papers (S1 Tables 1/2)")
      ->check(CLI::IsMember({"autotune", "papers"}))
      ->capture_default_str();
  cmd->add_option("--ff", o->ff, "friction feed-forward: coulomb (the rule) | stribeck (whole model) | off")
      ->check(CLI::IsMember({"coulomb", "stribeck", "off"}))
      ->capture_default_str();
  cmd->add_option("--observer", o->observer,
                  "speed observer (designed by the tuning library): speed (estimated speed fed back, the rule) | position "
                  "(estimated speed and position) | off (M-method speed)")
      ->check(CLI::IsMember({"speed", "position", "off"}))
      ->capture_default_str();
  cmd->add_option("--observer-sigma-v", o->observer_sigma_v_mm_s, "observer design: speed noise per tick, mm/s")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  cmd->add_option("--observer-sigma-d", o->observer_sigma_d_mm_s, "observer design: disturbance change per tick, mm/s")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  cmd->add_option("--observer-friction", o->observer_friction,
                  "on: the identified Coulomb friction in the observer's model (the rule) | off")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--scenario", o->tables,
                  "instead of the four S1 scenarios: identify THIS table (built-in name or TOML file, spindle off), "
                  "design from it and run the circle on it beside the papers' R-DVSC+DDC and the same design with "
                  "the observer off; repeat for more tables");
  cmd->callback([&run, o] { run = [o] { return run_best_circle_command(*o); }; });
}

}  // namespace tnv::cli
