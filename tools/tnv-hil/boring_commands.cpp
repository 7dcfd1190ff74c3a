// tnv-hil boring: the S4 adaptive boring infeed simulation (Lee 1983,
// Figs. 3 and 4): the firmware planner on the emulated node over CAN (or in
// this process, --planner direct) against the emulated process.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <functional>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "tools/can_emu/boring_machine_run.hpp"
#include "tools/can_emu/boring_node_sweep.hpp"
#include "tools/cli/output_path.hpp"
#include "tools/hil/boring_report.hpp"
#include "tools/hil/boring_sweep.hpp"
#include "tools/hil/plot_data.hpp"
#include "tools/score/boring_node_resolution.hpp"
#include "tools/tnv-hil/cli_support.hpp"
#include "tools/tnv-hil/commands.hpp"

namespace tnv::cli {

namespace {

struct BoringOptions {
  double sigma_mm = 0.016231;
  double alpha0 = 0.5;
  double s0_mm_rev = 0.5;
  int parts = 30;
  std::string change_at = "11,21";
  int seeds = 1;
  int first_seed = 1;
  bool json = false;
  std::string plot;
  std::string gain_form = "normalised";
  std::string reset_count = "measurements";
  int reset_after = 3;
  bool startup_in_rls = false;
  std::string log_base = "natural";
  double band_sigma_mm = 0.0;   // 0: same as --sigma-mm
  double gauge_sigma_mm = -1.0; // < 0: same as --sigma-mm
  std::string planner = "node";
  std::string scenario;         // empty: an exact gauge (the paper's setting)
  bool on_machine = false;      // every part a boring pass on the emulated machine
  bool segmented_pass = false;  // with on_machine: ~10 mm segments at the host's S(L), not one line along the depth
  double spindle_rpm = can_host::BoringMachineOptions{}.spindle_rpm;
};

// "11,21", "11" or "none"; nullopt with a message when malformed.
std::optional<std::vector<int>> parse_change_at(const std::string& text) {
  std::vector<int> out;
  if (text == "none") return out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, comma - start);
    try {
      std::size_t used = 0;
      const int v = std::stoi(item, &used);
      if (used != item.size()) throw std::invalid_argument(item);
      out.push_back(v);
    } catch (const std::exception&) {
      std::fprintf(stderr, "tnv-hil: --change-at: '%s' is not a part number (use e.g. 11,21 or none)\n", item.c_str());
      return std::nullopt;
    }
    start = comma + 1;
  }
  return out;
}

int run_boring_command(const BoringOptions& o) {
  hil::BoringRunRequest request = hil::paper_boring_request(o.sigma_mm, o.alpha0);
  request.planner.nominal_infeed_mm_rev = o.s0_mm_rev;
  request.planner.gain_form = o.gain_form == "kalman"    ? fw::BoringGainForm::kalman
                              : o.gain_form == "printed" ? fw::BoringGainForm::printed
                                                         : fw::BoringGainForm::normalised;
  request.planner.reset_count = o.reset_count == "parts"       ? fw::BoringResetCount::parts
                                : o.reset_count == "positions" ? fw::BoringResetCount::positions
                                                               : fw::BoringResetCount::measurements;
  request.planner.reset_after = o.reset_after;
  request.planner.startup_in_rls = o.startup_in_rls;
  request.planner.log_base = o.log_base == "decimal" ? fw::BoringLogBase::decimal : fw::BoringLogBase::natural;
  if (o.band_sigma_mm != 0.0) request.band_sigma_mm = o.band_sigma_mm;
  if (o.gauge_sigma_mm >= 0.0) request.process_sigma_mm = o.gauge_sigma_mm;
  if (!o.scenario.empty()) {
    const auto scenario = resolve_scenario_or_report(o.scenario);
    if (!scenario) return kExitBadInput;
    request = hil::with_scenario_gauge(request, *scenario);
  }
  request.parts = o.parts;
  const auto change_at = parse_change_at(o.change_at);
  if (!change_at) return kExitBadInput;
  request.change_at = *change_at;
  if (const std::string error = hil::validate_boring_request(request); !error.empty()) {
    std::fprintf(stderr, "tnv-hil: boring: %s\n", error.c_str());
    return kExitBadInput;
  }

  const bool on_node = o.planner == "node";
  if (const std::string why = hil::node_planner_refusal(request.planner, request.positions_mm); on_node && !why.empty()) {
    std::fprintf(stderr, "tnv-hil: boring: %s (the node does not carry it: add --planner direct)\n", why.c_str());
    return kExitBadInput;
  }

  can_host::BoringMachineOptions machine;
  machine.spindle_rpm = o.spindle_rpm;
  machine.along_depth = !o.segmented_pass;
  if (o.on_machine) {
    if (!on_node) {
      std::fprintf(stderr, "tnv-hil: boring: --on-machine runs the planner on the node (leave out --planner direct)\n");
      return kExitBadInput;
    }
    if (const std::string why = can_host::boring_machine_refusal(request, machine); !why.empty()) {
      std::fprintf(stderr, "tnv-hil: boring --on-machine: %s\n", why.c_str());
      return kExitBadInput;
    }
  } else if (o.segmented_pass) {
    std::fprintf(stderr, "tnv-hil: boring: --segmented-pass is a pass on the machine (add --on-machine)\n");
    return kExitBadInput;
  } else if (o.first_seed != 1) {
    std::fprintf(stderr, "tnv-hil: boring: --first-seed splits an --on-machine sweep (add --on-machine)\n");
    return kExitBadInput;
  }

  Progress progress("boring");
  // A pass on the machine takes about as long as 10,000 parts in process.
  const bool long_run = static_cast<long>(o.seeds) * o.parts * (o.on_machine ? 10'000 : 1) > 200'000;
  const hil::BoringProgress report_progress =
      long_run ? hil::BoringProgress(std::ref(progress)) : hil::BoringProgress{};
  std::string node_error;
  const hil::BoringSweepResult result =
      o.on_machine ? can_host::run_boring_sweep_on_machine(request, o.seeds, machine, report_progress,
                                                           static_cast<std::uint64_t>(o.first_seed))
      : on_node    ? can_host::run_boring_sweep_on_emulated_node(request, o.seeds, report_progress, node_error)
                   : hil::run_boring_sweep(request, o.seeds, report_progress);
  if (!node_error.empty()) {
    std::fprintf(stderr, "tnv-hil: boring: %s\n", node_error.c_str());
    return kExitFailure;
  }
  if (o.json)
    std::cout << hil::boring_sweep_json(request, result).dump(2) << '\n';
  else
    std::cout << hil::boring_sweep_text(request, result);
  bool ok = result.error.empty();
  if (!o.plot.empty()) {
    char title[200];
    std::snprintf(title, sizeof title, "S4 adaptive boring: sigma_d = %g mm, alpha0 = %g, S0 = %g mm/rev", o.sigma_mm,
                  o.alpha0, o.s0_mm_rev);
    ok = write_figure(o.plot, hil::boring_plot_data(title, request, result)) && ok;
  }
  if (!result.error.empty()) std::fprintf(stderr, "tnv-hil: run failed: %s\n", result.error.c_str());
  return ok ? kExitOk : kExitFailure;
}

}  // namespace

void add_boring_commands(CLI::App& app, Runner& run) {
  auto o = std::make_shared<BoringOptions>();
  CLI::App* cmd = app.add_subcommand("boring", "S4 adaptive boring infeed (RLS + variance perturbation) over parts");
  cmd->add_option("--sigma-mm", o->sigma_mm, "measurement noise sigma_d of the deflection (mm); band d0 +- 3 sigma_d")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--alpha0", o->alpha0, "start-up guess of alpha (paper: 0 < alpha0 <= 1)")
      ->check(CLI::Range(1e-6, 3.0))
      ->capture_default_str();
  cmd->add_option("--s0", o->s0_mm_rev, "nominal infeed S0 of part 1 (mm/rev)")->capture_default_str();
  cmd->add_option("--parts", o->parts, "parts per run")->check(CLI::Range(1, 100000))->capture_default_str();
  cmd->add_option("--change-at", o->change_at, "parts where the 2nd and 3rd parameter sets start, or none")
      ->capture_default_str();
  cmd->add_option("--seeds", o->seeds, "runs with gauge-noise seeds 1..N")->check(CLI::Range(1, 100000))->capture_default_str();
  cmd->add_option("--first-seed", o->first_seed,
                  "with --on-machine: seeds K..K+N-1 instead of 1..N (a long sweep split over processes)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "print JSON on stdout");
  cmd->add_option("--plot", o->plot, "write the figure (.svg, .png or .pdf)")->check(tnv::cli::PlotFile());
  cmd->add_option("--gain-form", o->gain_form, "Sigma in eqs. (5)/(6): normalised (1, 1) | kalman (Sigma, Sigma) | printed (Sigma, 1)")
      ->check(CLI::IsMember({"normalised", "kalman", "printed"}))
      ->capture_default_str();
  cmd->add_option("--reset-count", o->reset_count, "what 'three in a row' counts: measurements | parts | positions")
      ->check(CLI::IsMember({"measurements", "parts", "positions"}))
      ->capture_default_str();
  cmd->add_option("--reset-after", o->reset_after, "out-of-band results in a row that reset P")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  cmd->add_flag("--startup-in-rls", o->startup_in_rls, "also fit part 1's measurements by RLS after eq. (10)");
  cmd->add_option("--log-base", o->log_base, "log of the model: natural | decimal")
      ->check(CLI::IsMember({"natural", "decimal"}))
      ->capture_default_str();
  cmd->add_option("--band-sigma-mm", o->band_sigma_mm, "judge bad parts against d0 +- 3 this (default: --sigma-mm)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--planner", o->planner,
                  "node: every part through the emulated node over CAN (BORE_GAUGE); direct: the same planner in this "
                  "process at the node's resolution (faster; also runs --startup-in-rls and --log-base decimal)")
      ->check(CLI::IsMember({"node", "direct"}))
      ->capture_default_str();
  cmd->add_option("--gauge-sigma-mm", o->gauge_sigma_mm,
                  "noise of the emulated gauge, 0 = exact (default: --sigma-mm; the planner keeps --sigma-mm)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--scenario", o->scenario,
                  "measure with this table's bore gauge (built-in name or TOML file; [noise] bore_gauge_um_rms, "
                  "bore_gauge_resolution_um, seed): its error adds to the gauge noise; default: an exact gauge");
  cmd->add_flag("--segmented-pass", o->segmented_pass,
                "with --on-machine: the pass as ~10 mm segments, each fed per revolution at the host's S(L) at its "
                "middle, instead of one line along which the node follows its planner's S(L) every tick");
  cmd->add_flag("--on-machine", o->on_machine,
                "cut every part as a boring pass on the emulated machine: the node's infeeds as Z feed per spindle "
                "revolution, the bore gauged from the bar's deflection along the pass (slow: a pass is tens of "
                "seconds of machine time)");
  cmd->add_option("--spindle-rpm", o->spindle_rpm, "spindle speed of the passes (--on-machine)")
      ->check(CLI::Range(100.0, 6000.0))
      ->capture_default_str();
  cmd->callback([&run, o] { run = [o] { return run_boring_command(*o); }; });
}

}  // namespace tnv::cli
