// tnv-hil soak: an hour (by default) of circles and jogs on the HIL rig,
// wrapping the 32-bit tick counter several times, with the verdicts.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "firmware/tick/firmware_config.hpp"
#include "tools/cli/output_path.hpp"
#include "tools/hil/hil_rig.hpp"
#include "tools/hil/plot_data.hpp"
#include "tools/hil/soak_run.hpp"
#include "tools/tnv-hil/cli_support.hpp"
#include "tools/tnv-hil/commands.hpp"
#include "tools/hil/report.hpp"

namespace tnv::cli {

namespace {

struct SoakOptions {
  double hours = 1.0;
  std::string scenario = "no-cut";
  std::string controller = "rdvsc";
  bool json = false;
  std::string plot;
};

nlohmann::json metric_json(const hil::SoakMetric& m) { return {{"mean", m.mean}, {"std", m.std}}; }

nlohmann::json window_json(const hil::SoakWindow& w) {
  return {{"cycles", w.cycles},
          {"contour_max_um", metric_json(w.contour_max_um)},
          {"contour_mean_um", metric_json(w.contour_mean_um)},
          {"contour_std_um", metric_json(w.contour_std_um)},
          {"rest_error_um", metric_json(w.rest_error_um)},
          {"rest_d_hat_mm_s", metric_json(w.rest_d_hat_mm_s)},
          {"cycle_max_d_hat_mm_s", metric_json(w.cycle_d_hat_mm_s)}};
}

void print_window(const char* label, const hil::SoakWindow& w) {
  std::printf("  %s %2zu cycles: contour max %.3f +- %.3f um, mean %.3f um, std %.3f um; at rest |error| %.3f um, "
              "|d_hat| %.3f mm/s; cycle max |d_hat| %.3f mm/s\n",
              label, w.cycles, w.contour_max_um.mean, w.contour_max_um.std, w.contour_mean_um.mean,
              w.contour_std_um.mean, w.rest_error_um.mean, w.rest_d_hat_mm_s.mean, w.cycle_d_hat_mm_s.mean);
}

const char* yes_no(bool v) { return v ? "yes" : "NO"; }

int run_soak_command(const SoakOptions& o) {
  const auto scenario = resolve_scenario_or_report(o.scenario);
  if (!scenario) return kExitBadInput;
  hil::SoakRequest request;
  request.scenario = *scenario;
  const std::optional<fw::ControllerKind> controller = controller_or_report(o.controller);
  if (!controller) return kExitBadInput;
  request.controller = *controller;
  request.duration_s = o.hours * 3600.0;
  // Progress in simulated seconds, every 10%.
  int next_tenth = 1;
  request.progress = [&next_tenth](double done_s, double total_s) {
    if (done_s < total_s * next_tenth / 10.0) return;
    std::fprintf(stderr, "[soak] %.0f / %.0f s simulated\n", done_s, total_s);
    ++next_tenth;
  };
  const auto started = std::chrono::steady_clock::now();
  const hil::SoakResult r = hil::run_soak(request, fw::default_firmware_config());
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (!r.error.empty() && r.cycles.empty() && r.firmware_ticks == 0) {
    std::fprintf(stderr, "tnv-hil: %s\n", r.error.c_str());
    return kExitBadInput;  // refused before anything ran
  }
  std::fprintf(stderr, "[soak] %.0f s simulated in %.1f s wall (%.0fx real time)\n", r.simulated_s, wall_s,
               r.simulated_s / wall_s);

  if (o.json) {
    nlohmann::json cycles = nlohmann::json::array();
    for (const hil::SoakCycle& c : r.cycles) {
      cycles.push_back({{"start_s", c.start_s},
                        {"circle", hil::contour_stats_json(c.circle)},
                        {"rest_error_um", c.rest_error_um},
                        {"rest_d_hat_mm_s", c.rest_d_hat_mm_s},
                        {"max_abs_d_hat_mm_s", c.max_abs_d_hat_mm_s},
                        {"jog_max_following_um", c.jog_max_following_um},
                        {"clock_wraps", c.clock_wraps}});
    }
    nlohmann::json j = {{"scenario", scenario->name},
                        {"controller", o.controller},
                        {"simulated_s", r.simulated_s},
                        {"wall_s", wall_s},
                        {"completed", r.completed},
                        {"error", r.error},
                        {"firmware_ticks", r.firmware_ticks},
                        {"board_ticks", r.board_ticks},
                        {"missed_ticks", r.counters.missed_ticks},
                        {"late_ticks", r.counters.late_ticks},
                        {"bus_errors", r.counters.bus_errors},
                        {"clock_wraps", r.clock_wraps},
                        {"encoder_register_wraps", r.encoder_register_wraps},
                        {"max_encoder_drift_counts", r.max_encoder_drift_counts},
                        {"max_clock_drift_clocks", r.max_clock_drift_clocks},
                        {"max_abs_d_hat_mm_s", r.max_abs_d_hat_mm_s},
                        {"max_rest_error_um", r.max_rest_error_um},
                        {"first", window_json(r.first)},
                        {"last", window_json(r.last)},
                        {"no_missed_ticks", r.no_missed_ticks},
                        {"no_counter_drift", r.no_counter_drift},
                        {"stationary", r.stationary},
                        {"passed", r.passed()},
                        {"cycles", cycles}};
    std::cout << j.dump(2) << '\n';
  } else {
    std::printf("soak: %s, %s, %.0f s simulated (%.2f h), %zu cycles of circle + rest + 4 jogs\n",
                scenario->name.c_str(), o.controller.c_str(), r.simulated_s, r.simulated_s / 3600.0, r.cycles.size());
    std::printf("  ticks: firmware %llu, board %llu (+%d homing); missed %llu, late %llu, bus errors %llu\n",
                static_cast<unsigned long long>(r.firmware_ticks), static_cast<unsigned long long>(r.board_ticks),
                hil::HilRig::kHomingTicks, static_cast<unsigned long long>(r.counters.missed_ticks),
                static_cast<unsigned long long>(r.counters.late_ticks),
                static_cast<unsigned long long>(r.counters.bus_errors));
    std::printf("  32-bit clock wraps %u, 16-bit encoder register wraps %u\n", r.clock_wraps, r.encoder_register_wraps);
    std::printf("  drift: encoder count %lld counts, tick clock %lld clocks (worst tick)\n",
                static_cast<long long>(r.max_encoder_drift_counts), static_cast<long long>(r.max_clock_drift_clocks));
    print_window("first", r.first);
    print_window("last ", r.last);
    std::printf("  worst |d_hat| %.3f mm/s, worst rest error %.3f um\n", r.max_abs_d_hat_mm_s, r.max_rest_error_um);
    std::printf("  no missed ticks: %s; no counter drift: %s; stationary: %s\n", yes_no(r.no_missed_ticks),
                yes_no(r.no_counter_drift), yes_no(r.stationary));
  }
  bool ok = r.passed();
  if (!r.error.empty()) std::fprintf(stderr, "tnv-hil: soak: %s\n", r.error.c_str());
  if (!o.plot.empty()) ok = write_figure(o.plot, hil::soak_plot_data(r, scenario->name)) && ok;
  return ok ? kExitOk : kExitFailure;
}

}  // namespace

void add_soak_commands(CLI::App& app, Runner& run) {
  auto opts = std::make_shared<SoakOptions>();
  CLI::App* cmd = app.add_subcommand("soak", "circles and jogs for hours of simulated time: ticks, drift, stationarity");
  cmd->add_option("--hours", opts->hours, "simulated hours (the 32-bit clock wraps every 429.5 s)")
      ->check(CLI::Range(0.01, 100.0))
      ->capture_default_str();
  cmd->add_option("--scenario", opts->scenario, "built-in name or TOML file, without cutting")->capture_default_str();
  cmd->add_option("--controller", opts->controller, "pid | dvsc | rdvsc")
      ->check(CLI::IsMember({"pid", "dvsc", "rdvsc"}))
      ->capture_default_str();
  cmd->add_flag("--json", opts->json, "print JSON on stdout (with every cycle)");
  cmd->add_option("--plot", opts->plot, "write the per-cycle figure (.svg, .png or .pdf)")->check(tnv::cli::PlotFile());
  cmd->callback([&run, opts] { run = [opts] { return run_soak_command(*opts); }; });
}

}  // namespace tnv::cli
