// tnv-hil freq-response: `tnvctl freq-response` on the emulated controller
// with a chosen scenario (the same CAN path, docs/frequency-response.md).
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>

#include "hal/axis_choice.hpp"
#include "tools/can_emu/emulated_bus.hpp"
#include "tools/can/freq_response_cli.hpp"
#include "tools/can/freq_response_json.hpp"
#include "tools/can/freq_response_run.hpp"
#include "tools/can/freq_response_text.hpp"
#include "tools/cli/output_path.hpp"
#include "tools/cli/run_plotter.hpp"
#include "tools/tnv-hil/commands.hpp"

namespace tnv::cli {

namespace {

struct FreqCli {
  std::string axis = "x";
  std::string scenario = "no-cut";
  std::string plot;
  bool json = false;
  can_host::FreqResponseOptions run{};
};

int run_freq_command(const FreqCli& c) {
  can_host::FreqResponseOptions o = c.run;
  if (const std::string e = can_host::check_options(o); !e.empty()) {
    std::fprintf(stderr, "tnv-hil: freq-response: %s\n", e.c_str());
    return kExitBadInput;
  }
  // A node of its own: nothing stored (a fresh node, the scenario's table).
  const std::string storage =
      (std::filesystem::temp_directory_path() / ("tnv-hil-freq-" + std::to_string(getpid()) + ".bin")).string();
  std::filesystem::remove(storage);
  can_host::EmulatedNodeOptions node;
  node.scenario = c.scenario;
  node.storage_path = storage;
  std::string error;
  std::unique_ptr<can_host::EmulatedBus> bus = can_host::EmulatedBus::create(node, error);
  if (!bus) {
    std::fprintf(stderr, "tnv-hil: freq-response: %s\n", error.c_str());
    return kExitBadInput;
  }
  const hal::Axis axis = hal::axis_from_name(c.axis).value_or(hal::Axis::x);
  const emu::AxisPlantParams& p = bus->scenario().plant[hal::index(axis)];
  o.plant_model = fw::zoh_axis_model(p.tau_s, p.gain, fw::kControlPeriod_s);
  int code = kExitOk;
  try {
    can_host::NodeClient client(*bus, bus->node_id());
    client.command(fw::can::CommandCode::enable);
    client.pump(can_host::Micros{300'000});
    const can_host::FreqResponseResult r = can_host::run_freq_response(client, axis, o);
    nlohmann::json j = can_host::freq_response_json(r);
    j["scenario"] = c.scenario;
    if (c.json)
      std::printf("%s\n", j.dump(2).c_str());
    else
      std::printf("scenario %s\n%s", c.scenario.c_str(), can_host::freq_response_text(r).c_str());
    if (!c.plot.empty()) {
      nlohmann::json data = j;
      data["kind"] = "bode";
      if (!plot_json(c.plot, data, "tnv-hil")) code = kExitFailure;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tnv-hil: freq-response: %s\n", e.what());
    code = kExitFailure;
  }
  bus.reset();
  std::filesystem::remove(storage);
  return code;
}

}  // namespace

void add_freq_response_commands(CLI::App& app, Runner& run) {
  auto o = std::make_shared<FreqCli>();
  CLI::App* cmd = app.add_subcommand(
      "freq-response",
      "frequency response on the emulated controller (tnvctl freq-response with --scenario): the plant from an "
      "open-loop multisine, the open / closed loop from a multisine or sweep added to the holding controller's "
      "command (on a slow carrier motion, --carrier), coherence, margins measured vs the model; the closed-loop "
      "experiment's level, tones and duration default by the active controller (docs/frequency-response.md)");
  cmd->add_option("--axis", o->axis, hal::kAxisChoices)
      ->check(CLI::IsMember(std::vector<std::string>(hal::kAxisNames.begin(), hal::kAxisNames.end())))->capture_default_str();
  cmd->add_option("--scenario", o->scenario, "built-in scenario name or TOML file")->capture_default_str();
  can_host::add_freq_response_options(*cmd, o->run);
  cmd->add_option("--plot", o->plot, "write the Bode plot (.svg, .png or .pdf)")->check(PlotFile());
  cmd->add_flag("--json", o->json, "print JSON");
  cmd->callback([o, &run] { run = [o] { return run_freq_command(*o); }; });
}

}  // namespace tnv::cli
