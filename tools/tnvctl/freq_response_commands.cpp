// tnvctl freq-response: the frequency response of an axis on the target
// (a closed-loop EXCITE multisine or sweep, the node's capture, the host's
// estimate; docs/frequency-response.md).
#include <memory>
#include <string>

#include "firmware/can/protocol_enums.hpp"
#include "hal/axis_choice.hpp"
#include "tools/can/freq_response_cli.hpp"
#include "tools/can/freq_response_json.hpp"
#include "tools/can/freq_response_run.hpp"
#include "tools/can/freq_response_text.hpp"
#include "tools/cli/output_path.hpp"
#include "tools/cli/run_plotter.hpp"
#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

namespace {

struct FreqOptions {
  std::string axis = "x";
  std::string plot;
  can_host::FreqResponseOptions run{};
};

can_host::FreqResponseOptions checked_options(const FreqOptions& o) {
  const can_host::FreqResponseOptions& run = o.run;
  if (const std::string e = can_host::check_options(run); !e.empty()) throw BadInput(e);
  return run;
}

int run_freq(const FreqOptions& o, Session& session, Report& report) {
  can_host::FreqResponseOptions run = checked_options(o);
  const hal::Axis axis = hal::axis_from_name(o.axis).value_or(hal::Axis::x);
  can_host::NodeClient& client = session.client();
  if (const can_host::EmulatedBus* emu = session.emulated()) {
    // The emulated table's own plant for the model side, and servo on (a
    // fresh emulated node starts disabled; a real one is enabled by its operator).
    const emu::AxisPlantParams& p = emu->scenario().plant[hal::index(axis)];
    run.plant_model = fw::zoh_axis_model(p.tau_s, p.gain, fw::kControlPeriod_s);
    client.command(fw::can::CommandCode::enable);
    client.pump(can_host::Micros{300'000});
  }
  const can_host::FreqResponseResult result = can_host::run_freq_response(client, axis, run);
  const nlohmann::json json = can_host::freq_response_json(result);
  report.data.update(json);
  report.line(can_host::freq_response_text(result));
  if (!o.plot.empty()) {
    const std::string data = cli::plot_data_path(o.plot);
    if (!cli::write_file_replacing(data, json.dump(1)))
      throw RunFailed(data + ": cannot write");
    const std::string error = cli::run_plotter("bode", {data}, o.plot);
    if (!error.empty()) throw RunFailed(error);
    report.line("[plot] wrote " + o.plot);
    report.data["plot"] = o.plot;
  }
  return kExitOk;
}

}  // namespace

void add_freq_response_commands(CLI::App& app, ActionSlot& slot) {
  auto o = std::make_shared<FreqOptions>();
  CLI::App* cmd = app.add_subcommand(
      "freq-response",
      "frequency response of an axis: a closed-loop EXCITE (multisine or sweep added to the holding controller's "
      "command) recorded at every tick by the node's capture; prints the plant, open- or closed-loop response "
      "with coherence and the model's, and the margins measured vs the model (docs/frequency-response.md); the "
      "closed-loop experiment rides on a slow carrier motion (--carrier) and its level, tones and duration "
      "default by the active controller; the node must be enabled and holding (--emu: enabled here)");
  cmd->add_option("--axis", o->axis, hal::kAxisChoices)
      ->check(CLI::IsMember(std::vector<std::string>(hal::kAxisNames.begin(), hal::kAxisNames.end())))->capture_default_str();
  can_host::add_freq_response_options(*cmd, o->run);
  cmd->add_option("--plot", o->plot, "write the Bode plot (.svg, .png or .pdf)")->check(tnv::cli::PlotFile());
  cmd->callback([&slot, o] {
    slot = Action{"freq-response", true, [o](Session& s, Report& r) { return run_freq(*o, s, r); },
                  [o] { checked_options(*o); }};
  });
}

}  // namespace tnv::tnvctl
