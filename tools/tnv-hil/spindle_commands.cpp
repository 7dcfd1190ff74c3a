// tnv-hil spindle-safety: every transition after which the spindle must not
// start by itself, on the emulated machine, judged from the emulator's
// truth (tools/hil/spindle_safety_run.hpp; docs/safety.md "Spindle").
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "tools/hil/spindle_safety_run.hpp"
#include "tools/tnv-hil/cli_support.hpp"
#include "tools/tnv-hil/commands.hpp"

namespace tnv::cli {

namespace {

struct SpindleSafetyOptions {
  bool json = false;
  std::string scenario = "no-cut";
};

int run_spindle_safety_command(const SpindleSafetyOptions& o) {
  const std::optional<emu::Scenario> scenario = resolve_scenario_or_report(o.scenario);
  if (!scenario) return kExitBadInput;
  const hil::SpindleSafetySummary s = hil::run_spindle_safety(*scenario);
  if (o.json) {
    nlohmann::json runs = nlohmann::json::array();
    for (const hil::SpindleTransitionResult& r : s.transitions)
      runs.push_back({{"transition", r.name},
                      {"stop_cause", r.stop_cause},
                      {"stopped", r.stopped},
                      {"self_start", r.self_start},
                      {"rise_rpm", r.rise_rpm},
                      {"refused_while_turning", r.refused_while_turning},
                      {"restarted", r.restarted},
                      {"program_end_stop", r.program_end_stop},
                      {"feed_onsets", r.feed_onsets},
                      {"feed_before_at_speed", r.feed_before_at_speed},
                      {"ok", r.ok()}});
    const nlohmann::json out = {{"scenario", scenario->name},
                                {"transitions", s.transitions.size()},
                                {"self_starts", s.self_starts},
                                {"feed_before_at_speed", s.feed_before_at_speed},
                                {"feed_onsets", s.feed_onsets},
                                {"all_ok", s.all_ok},
                                {"judge", "the emulator's spindle speed and tool speed; a feed start as tnv-hil "
                                          "path judges it (at speed: the drive's command steady for 10 ticks and "
                                          "its speed within 5 % or 20 rpm of it); a self-start: a rise of more "
                                          "than 10 rpm without a start"},
                                {"runs", runs}};
    std::cout << out.dump(2) << "\n";
  } else {
    std::printf("spindle-safety on %s: start, a program of feed moves, the transition, 3 s watched, a new start and "
                "a second program\n",
                scenario->name.c_str());
    std::printf("%-15s %-13s %8s %10s %9s %10s %9s %7s %6s %4s\n", "transition", "stop_cause", "stopped", "rise_rpm",
                "restarted", "end_stops", "load_ref", "onsets", "early", "ok");
    for (const hil::SpindleTransitionResult& r : s.transitions)
      std::printf("%-15s %-13s %8s %10.3f %9s %10s %9s %7u %6u %4s\n", r.name.c_str(), r.stop_cause.c_str(),
                  r.stopped ? "yes" : "NO", r.rise_rpm, r.restarted ? "yes" : "NO", r.program_end_stop ? "yes" : "NO",
                  r.refused_while_turning ? "yes" : "NO", r.feed_onsets, r.feed_before_at_speed, r.ok() ? "yes" : "NO");
    std::printf("transitions %zu, self_starts %u, feed_before_at_speed %u (of %u feed onsets)\n", s.transitions.size(),
                s.self_starts, s.feed_before_at_speed, s.feed_onsets);
  }
  if (!s.all_ok) std::fprintf(stderr, "tnv-hil spindle-safety: a transition failed (see the table)\n");
  return s.all_ok ? kExitOk : kExitFailure;
}

}  // namespace

void add_spindle_commands(CLI::App& app, Runner& run) {
  auto o = std::make_shared<SpindleSafetyOptions>();
  CLI::App* cmd = app.add_subcommand(
      "spindle-safety",
      "every transition after which the spindle must stay off (feed hold, abort, fault clear, e-stop release, host "
      "timeout, node restart, parameter load): self-starts and feed moves before at-speed, from the emulator");
  cmd->add_flag("--json", o->json, "JSON on stdout");
  cmd->add_option("--scenario", o->scenario, "the machine (built-in name or TOML file)")->capture_default_str();
  cmd->callback([o, &run]() { run = [o]() { return run_spindle_safety_command(*o); }; });
}

}  // namespace tnv::cli
