// tnv-hil faults: every injected fault of the safety table on the HIL rig,
// with what the supervisor latched and when the board's outputs were safe.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "hal/axis_choice.hpp"
#include "tools/hil/fault_run.hpp"
#include "tools/hil/fault_verdict.hpp"
#include "tools/tnv-hil/cli_support.hpp"
#include "tools/tnv-hil/commands.hpp"

namespace tnv::cli {

namespace {

struct FaultsOptions {
  std::string scenario = "no-cut";
  std::string controller = "rdvsc";
  std::string only;
  bool json = false;
};

std::string ms_text(std::optional<double> s) {
  if (!s) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", *s * 1e3);
  return buf;
}

int run_faults_command(const FaultsOptions& o) {
  const auto scenario = resolve_scenario_or_report(o.scenario);
  if (!scenario) return kExitBadInput;
  std::vector<hil::FaultCase> cases = hil::standard_fault_cases();
  if (!o.only.empty()) {
    std::erase_if(cases, [&](const hil::FaultCase& c) { return c.name != o.only; });
    if (cases.empty()) {
      std::fprintf(stderr, "tnv-hil: --only %s: no such fault case\n", o.only.c_str());
      return kExitBadInput;
    }
  }
  const std::uint32_t mid_code = std::uint32_t{1} << (scenario->dac.bits - 1);
  const std::optional<fw::ControllerKind> kind = controller_or_report(o.controller);
  if (!kind) return kExitBadInput;
  const fw::ControllerKind controller = *kind;
  nlohmann::json rows = nlohmann::json::array();
  std::string text =
      "fault              motion  expected             latched              axis  ticks  time to safe ms  deviation um  "
      "verdict\n";
  int failed = 0;
  for (const hil::FaultCase& c : cases) {
    const hil::FaultObservation obs = hil::run_fault_case(*scenario, c, controller);
    const bool ok = hil::fault_case_met(c, obs, mid_code);
    if (!ok) ++failed;
    const char* latched = hil::latched_text(obs);
    const std::string axis = obs.fault.axis < 0 ? "-" : std::string(hal::axis_label_or(obs.fault.axis, "?"));
    char line[256];
    std::snprintf(line, sizeof line, "%-18s %-7s %-20s %-20s %-5s %5llu  %15s  %12.1f  %s\n", c.name.c_str(),
                  hil::to_string(c.motion), fw::to_string(c.expected), latched, axis.c_str(),
                  static_cast<unsigned long long>(obs.ticks_to_detect()), ms_text(obs.time_to_safe_s()).c_str(),
                  obs.deviation_um, ok ? "ok" : (obs.error.empty() ? "NOT MET" : obs.error.c_str()));
    text += line;
    rows.push_back(hil::fault_case_json(c, obs, ok));
  }
  const hil::WatchdogObservation wd = hil::run_watchdog_case(*scenario, 3.0, 10.0, controller);
  const std::optional<double> wd_trip_after_kick_s =
      wd.trip_s ? std::optional<double>(*wd.trip_s - wd.last_kick_s) : std::nullopt;
  const bool wd_ok = wd.error.empty() && wd.trip_s && wd.at_trip.safe(mid_code) &&
                     hil::every_command_zero(wd.command_at_trip_mm_s);
  if (!wd_ok) ++failed;
  if (o.json) {
    nlohmann::json j = {{"scenario", scenario->name},
                        {"controller", o.controller},
                        {"faults", rows},
                        {"watchdog",
                         {{"hang_ms", 10.0},
                          {"trip_after_last_kick_ms", wd_trip_after_kick_s ? nlohmann::json(*wd_trip_after_kick_s * 1e3)
                                                                           : nlohmann::json()},
                          {"fault_on_return", fw::to_string(wd.fault_on_return.reason)},
                          {"clear_while_tripped", fw::to_string(wd.clear_while_tripped)},
                          {"clear_after_reset", fw::to_string(wd.clear_after_reset)},
                          {"ok", wd_ok}}}};
    std::cout << j.dump(2) << '\n';
  } else {
    std::cout << "scenario " << scenario->name << ", controller " << o.controller
              << "; faults injected 3.0004 s into the run (2.5 s into the circle) unless noted\n"
              << text;
    std::printf("watchdog (firmware hangs for 10 ms mid-circle): outputs safe %s ms after the last kick; on return "
                "the firmware latches %s; clear %s while tripped, %s after the board reset  %s\n",
                ms_text(wd_trip_after_kick_s).c_str(), fw::to_string(wd.fault_on_return.reason),
                fw::to_string(wd.clear_while_tripped), fw::to_string(wd.clear_after_reset), wd_ok ? "ok" : "NOT MET");
  }
  if (failed > 0) std::fprintf(stderr, "tnv-hil: %d fault case(s) not met\n", failed);
  return failed == 0 ? kExitOk : kExitFailure;
}

}  // namespace

void add_fault_commands(CLI::App& app, Runner& run) {
  auto opts = std::make_shared<FaultsOptions>();
  CLI::App* cmd = app.add_subcommand("faults", "inject every fault of the safety table and time the safe state");
  cmd->add_option("--scenario", opts->scenario, "built-in name or TOML file (its own [[fault]]s stay in)")
      ->capture_default_str();
  cmd->add_option("--controller", opts->controller, "pid | dvsc | rdvsc")
      ->check(CLI::IsMember({"pid", "dvsc", "rdvsc"}))
      ->capture_default_str();
  cmd->add_option("--only", opts->only, "run one case by name (e.g. estop, runaway)");
  cmd->add_flag("--json", opts->json, "print JSON on stdout");
  cmd->callback([&run, opts] { run = [opts] { return run_faults_command(*opts); }; });
}

}  // namespace tnv::cli
