// tnv-hil bus-stress: hosts, tags and transmit priority on a flooded
// emulated bus (tools/can_emu/bus_stress.hpp). Prints the counts; exit 1 when
// a goal of docs/safety.md "Bus priority, tags, hosts and ownership" is missed.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "tools/can_emu/bus_stress.hpp"
#include "tools/tnv-hil/cli_support.hpp"
#include "tools/tnv-hil/commands.hpp"

namespace tnv::cli {

namespace {

struct BusStressCli {
  std::string flood_id = "0x7ff";
  double load = 1.0;
  int hosts = 2;
  std::string scenario = "no-cut";
  bool json = false;
};

int run_bus_stress_command(const BusStressCli& c) {
  can_host::BusStressOptions o;
  try {
    std::size_t used = 0;
    const unsigned long id = std::stoul(c.flood_id, &used, 16);
    if (used != c.flood_id.size()) throw std::invalid_argument("trailing characters");
    o.flood_id = static_cast<std::uint32_t>(id);
  } catch (const std::exception&) {
    std::fprintf(stderr, "tnv-hil: --flood-id %s: not a hexadecimal identifier\n", c.flood_id.c_str());
    return kExitBadInput;
  }
  o.load = c.load;
  o.hosts = c.hosts;
  o.scenario = c.scenario;
  if (const std::string why = can_host::validate(o); !why.empty()) {
    std::fprintf(stderr, "tnv-hil: %s\n", why.c_str());
    return kExitBadInput;
  }
  const can_host::BusStressResult r = can_host::run_bus_stress(o);
  if (!r.error.empty()) {
    std::fprintf(stderr, "tnv-hil: bus-stress: %s\n", r.error.c_str());
    return kExitFailure;
  }
  const bool goals = r.replies_received == r.requests && r.replies_misattributed == 0 &&
                     r.heartbeat_max_gap_ms <= 200.0 && r.fault_event_delay_ms >= 0.0 &&
                     r.fault_event_delay_ms <= 10.0 && r.missed_ticks == 0 && r.staged_sets_crossed == 0;
  if (c.json) {
    nlohmann::json j;
    j["flood_id"] = o.flood_id;
    j["load"] = o.load;
    j["hosts"] = o.hosts;
    j["requests"] = r.requests;
    j["replies_received"] = r.replies_received;
    j["replies_misattributed"] = r.replies_misattributed;
    j["replies_stale"] = r.replies_stale;
    j["heartbeat_max_gap_ms"] = r.heartbeat_max_gap_ms;
    j["fault_event_delay_ms"] = r.fault_event_delay_ms;
    j["missed_ticks"] = r.missed_ticks;
    j["late_ticks"] = r.late_ticks;
    j["staged_sets_crossed"] = r.staged_sets_crossed;
    j["commits"] = r.commits;
    j["flood_frames"] = r.flood_frames;
    j["bus_load"] = r.bus_load;
    j["telemetry_dropped"] = r.telemetry_dropped;
    j["node_tx_dropped"] = r.node_tx_dropped;
    j["goals_met"] = goals;
    std::cout << j.dump(2) << '\n';
  } else {
    std::printf("bus-stress: flood id 0x%03x at load %.2f (measured %.3f), %d hosts, scenario %s\n", o.flood_id, o.load,
                r.bus_load, o.hosts, o.scenario.c_str());
    std::printf("requests               %llu\n", static_cast<unsigned long long>(r.requests));
    std::printf("replies_received       %llu\n", static_cast<unsigned long long>(r.replies_received));
    std::printf("replies_misattributed  %llu\n", static_cast<unsigned long long>(r.replies_misattributed));
    std::printf("replies_stale          %llu\n", static_cast<unsigned long long>(r.replies_stale));
    std::printf("heartbeat_max_gap_ms   %.1f\n", r.heartbeat_max_gap_ms);
    std::printf("fault_event_delay_ms   %.1f\n", r.fault_event_delay_ms);
    std::printf("missed_ticks           %llu\n", static_cast<unsigned long long>(r.missed_ticks));
    std::printf("late_ticks             %llu\n", static_cast<unsigned long long>(r.late_ticks));
    std::printf("staged_sets_crossed    %llu (of %llu commits)\n", static_cast<unsigned long long>(r.staged_sets_crossed),
                static_cast<unsigned long long>(r.commits));
    std::printf("telemetry_dropped      %llu\n", static_cast<unsigned long long>(r.telemetry_dropped));
    std::printf("goals                  %s\n", goals ? "met" : "MISSED");
  }
  return goals ? kExitOk : kExitFailure;
}

}  // namespace

void add_bus_stress_commands(CLI::App& app, Runner& run) {
  auto o = std::make_shared<BusStressCli>();
  CLI::App* cmd = app.add_subcommand(
      "bus-stress",
      "flood the emulated CAN bus while the circle runs, send requests from several hosts and an ESTOP: replies, "
      "misattributions, heartbeat gap, FAULT_EVENT delay, missed ticks, crossed staged sets");
  cmd->add_option("--flood-id", o->flood_id, "identifier of the flood frames, hexadecimal")->capture_default_str();
  cmd->add_option("--load", o->load, "share of the wire the flood offers, 0 .. 1")->capture_default_str();
  cmd->add_option("--hosts", o->hosts, "requesting hosts (ids 1 .. N), 1 .. 4")->capture_default_str();
  cmd->add_option("--scenario", o->scenario, "built-in scenario name or TOML file")->capture_default_str();
  cmd->add_flag("--json", o->json, "print JSON");
  cmd->callback([o, &run] { run = [o] { return run_bus_stress_command(*o); }; });
}

}  // namespace tnv::cli
