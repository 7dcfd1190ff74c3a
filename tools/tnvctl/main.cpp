// tnvctl: tune a TNV-40 node over CAN from a laptop, on a real bus
// (SocketCAN) or on the in-process emulated controller. The command
// families live in *_commands.cpp.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "firmware/can/can_id.hpp"
#include "tools/cli/cli_frame.hpp"
#include "tools/cli/output_path.hpp"
#include "tools/tnvctl/commands.hpp"

int main(int argc, char** argv) {
  using namespace tnv::tnvctl;
  CLI::App app{
      "tnvctl: read and change a TNV-40 node's parameters, run motions, monitor it and capture at full tick rate, "
      "over CAN (--iface can0) or on the emulated controller (--emu)"};
  app.footer(
      "Exit codes: 0 ok; 1 refused by the node (the message names the ErrorCode and the parameter), timeout, "
      "device or bus error, a motion that ended in a fault, an output not written; 2 bad command line or input "
      "(nothing was sent).\n"
      "--json prints one JSON object per command on stdout (one per line in `script`), with \"ok\", "
      "\"exit_code\" and \"error\"; `monitor --json` streams one object per sample (JSON Lines) on stdout and "
      "its summary object on stderr.\n"
      "With --emu the node lives inside this process: use `tnvctl --emu script FILE` for several steps on one "
      "node; its parameters persist only through `params save` (--emu-storage).");
  app.require_subcommand(1);
  app.fallthrough();  // global options may also follow the subcommand
  tnv::cli::add_version_flag(app, "tnvctl");

  GlobalOptions g;
  CLI::Option* iface = app.add_option("--iface", g.iface, "SocketCAN interface (e.g. can0), or unix:PATH for tnv-fw's Unix-socket CAN link");
  CLI::Option* emu = app.add_flag("--emu", g.emu, "the in-process emulated controller (real firmware, emulated table)");
  iface->excludes(emu);
  app.add_option("--node", g.node, "node id")->check(CLI::Range(1, int{tnv::fw::can::kMaxNodeId}))->capture_default_str();
  app.add_option("--host-id", g.host_id,
                 "this host's id on the bus (request tags, its own staged parameter set, command ownership: taken "
                 "when a command needs it, released at the end)")
      ->check(CLI::Range(1, 15))
      ->capture_default_str();
  app.add_flag("--json", g.json, "machine-readable output on stdout");
  app.add_option("--timeout-ms", g.timeout_ms, "reply timeout per request (emulated: simulated ms)")
      ->check(CLI::Range(1, 600000))
      ->capture_default_str();
  app.add_option("--emu-scenario", g.emu_scenario, "emulated table: built-in scenario name or TOML file")
      ->needs(emu)
      ->capture_default_str();
  app.add_option("--emu-seed", g.emu_seed, "emulated encoder phase / cutting phase seed (0: as written, tnv-hil's default)")
      ->needs(emu)
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  app.add_option("--emu-storage", g.emu_storage,
                 "emulated node's parameter file (default $XDG_STATE_HOME/tnvctl/emu-node.params or "
                 "~/.local/state/tnvctl/emu-node.params)")
      ->needs(emu);

  app.add_option("--trace", g.trace,
                 "record every CAN frame sent and received to FILE in candump -l format (tnvctl decode reads it)")
      ->check(tnv::cli::OutputFile());

  ActionSlot slot;
  add_device_commands(app, slot);
  add_script_commands(app, slot);
#ifdef TNV_HAVE_SERVE
  add_serve_commands(app, slot);
#endif

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return tnv::cli::report_parse_error(app, e, "tnvctl", kExitBadInput);
  }
  if (!slot) return kExitBadInput;
  if (slot->needs_device && g.iface.empty() && !g.emu) {
    std::fprintf(stderr, "tnvctl: %s: which node? give --iface IFACE (SocketCAN, e.g. can0) or --emu (the emulated controller)\n",
                 slot->name.c_str());
    return kExitBadInput;
  }
  Session session(g);
  const int code = run_action(*slot, session);
  session.end();
  // The emulated node ends with this process: say so when changes would be lost.
  if (const tnv::can_host::EmulatedBus* emulated = session.opened_emulation();
      emulated != nullptr && emulated->node().params_unsaved())
    std::fprintf(stderr,
                 "tnvctl: note: the emulated node's unsaved parameter changes end with this process "
                 "(`params save` keeps them in %s)\n",
                 emulated->storage_path().c_str());
  return code;
}
