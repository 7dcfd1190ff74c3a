// tnv-hil rt-budget: the time each kind of CAN request costs the real-time
// loop while the servo holds (host CPU and modelled board time), and the
// ticks the board lost.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "firmware/tick/work_meter.hpp"
#include "tools/hil/rt_budget.hpp"
#include "tools/tnv-hil/cli_support.hpp"
#include "tools/tnv-hil/commands.hpp"

namespace tnv::cli {

namespace {

struct RtBudgetCliOptions {
  hil::RtBudgetOptions run;
  bool json = false;
};

nlohmann::json budget_row_json(const hil::RtBudgetRow& r) {
  return {{"kind", r.kind},
          {"calls", r.calls},
          {"max_call_us", r.max_call_us},
          {"p999_call_us", r.p999_call_us},
          {"max_board_us", r.max_board_us},
          {"p999_board_us", r.p999_board_us},
          {"refused", r.refused}};
}

int run_rt_budget_command(const RtBudgetCliOptions& o) {
  const hil::RtBudgetResult r = hil::run_rt_budget(o.run);
  if (!r.error.empty()) {
    std::fprintf(stderr, "tnv-hil rt-budget: %s\n", r.error.c_str());
    return kExitBadInput;
  }
  const bool met = r.missed_ticks == 0 && r.late_ticks == 0 && r.held;
  // Board time is the work meter's: a build without it shows zeros, not a fast board.
  const bool metered = fw::work_meter_enabled();
  if (!metered) {
    std::fprintf(stderr,
                 "tnv-hil rt-budget: warning: this tnv-hil is built without the work meter (TNV_WORK_METER=OFF): "
                 "no board time is modelled (the board columns are 0) and no call is charged\n");
  }
  if (o.json) {
    nlohmann::json kinds = nlohmann::json::array();
    for (const hil::RtBudgetRow& k : r.kinds) kinds.push_back(budget_row_json(k));
    nlohmann::json out = {{"scenario", o.run.scenario},
                          {"rounds", o.run.rounds},
                          {"clock", "thread_cpu"},
                          {"max_call_us", r.overall.max_call_us},
                          {"p999_call_us", r.overall.p999_call_us},
                          {"max_board_us", r.overall.max_board_us},
                          {"p999_board_us", r.overall.p999_board_us},
                          {"calls", r.overall.calls},
                          {"missed_ticks", r.missed_ticks},
                          {"late_ticks", r.late_ticks},
                          {"ticks", r.ticks},
                          {"requests", r.requests},
                          {"replies", r.replies},
                          {"refused", r.refused},
                          {"upload_frames", r.upload_frames},
                          {"worker_jobs", r.worker_jobs},
                          {"charged_calls", r.charged.charged_calls},
                          {"charged_us", static_cast<double>(r.charged.charged_ns) * 1e-3},
                          {"held", r.held},
                          {"kinds", kinds}};
    if (!metered) out["board_time_metered"] = false;
    std::cout << out.dump(2) << "\n";
  } else {
    std::printf("rt-budget: %s, %d rounds, %llu ticks, %llu requests (%llu answers, %llu refused), %llu upload frames, "
                "%llu worker jobs off the loop (saves, loads, shaper designs)\n",
                o.run.scenario.c_str(), o.run.rounds, static_cast<unsigned long long>(r.ticks),
                static_cast<unsigned long long>(r.requests), static_cast<unsigned long long>(r.replies),
                static_cast<unsigned long long>(r.refused), static_cast<unsigned long long>(r.upload_frames),
                static_cast<unsigned long long>(r.worker_jobs));
    std::printf("per call: host CPU time (thread clock) and modelled board time (work meter), us\n"
                "%-18s %8s %12s %13s %13s %14s %8s\n",
                "kind", "calls", "max_call_us", "p999_call_us", "max_board_us", "p999_board_us", "refused");
    const auto line = [](const hil::RtBudgetRow& k) {
      std::printf("%-18s %8llu %12.1f %13.1f %13.1f %14.1f %8llu\n", k.kind.c_str(),
                  static_cast<unsigned long long>(k.calls), k.max_call_us, k.p999_call_us, k.max_board_us,
                  k.p999_board_us, static_cast<unsigned long long>(k.refused));
    };
    for (const hil::RtBudgetRow& k : r.kinds) line(k);
    line(r.overall);
    std::printf("missed_ticks %llu, late_ticks %llu, charged calls %llu (%.1f us), servo %s\n",
                static_cast<unsigned long long>(r.missed_ticks), static_cast<unsigned long long>(r.late_ticks),
                static_cast<unsigned long long>(r.charged.charged_calls),
                static_cast<double>(r.charged.charged_ns) * 1e-3, r.held ? "holding" : "NOT holding");
  }
  if (!met) std::fprintf(stderr, "tnv-hil rt-budget: ticks lost or the servo did not hold\n");
  return met ? kExitOk : kExitFailure;
}

}  // namespace

void add_rt_budget_commands(CLI::App& app, Runner& run) {
  auto o = std::make_shared<RtBudgetCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "rt-budget", "CPU and modelled board time per CAN request kind on the real-time loop while the servo holds; missed and late ticks");
  cmd->add_option("--scenario", o->run.scenario, "built-in scenario or TOML file")->capture_default_str();
  cmd->add_option("--rounds", o->run.rounds, "times the scripted session runs")->capture_default_str()->check(
      CLI::Range(1, 100000));
  cmd->add_flag("--json", o->json, "JSON on stdout");
  cmd->callback([o, &run]() { run = [o]() { return run_rt_budget_command(*o); }; });
}

}  // namespace tnv::cli
