// tnv-board-emu: the emulated I/O board and TNV-40 table as a process,
// serving the register transport on a Unix socket (docs/hil-rig.md).
// Exit codes: 0 stopped (SIGTERM/SIGINT, or --once after the firmware
// left), 1 the socket failed, 2 bad command line or scenario.
#include <signal.h>
#include <sys/signalfd.h>
#include <poll.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

#include "drivers/linux/register_server.hpp"
#include "drivers/linux/stop_signals.hpp"
#include "drivers/linux/unix_seqpacket.hpp"
#include "emulator/machine.hpp"
#include "emulator/scenario_file.hpp"
#include "tools/cli/cli_frame.hpp"
#include "tools/tnv-board-emu/ticking_bus.hpp"

namespace {

using namespace tnv;

void report(const emu::Machine& machine, std::uint64_t ticks, const char* why) {
  std::printf("tnv-board-emu: %s after %llu ticks (t = %.3f s", why, static_cast<unsigned long long>(ticks),
              machine.time_s());
  for (const hal::Axis a : hal::kAxes) std::printf(", %s = %.4f mm", hal::axis_label(a), machine.truth(a).position_mm);
  std::printf(")\n");
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Emulated TNV-40 I/O board and table, served over the register transport"};
  std::string socket_path;
  std::string scenario_name = "no-cut";
  bool once = false;
  app.add_option("--socket", socket_path, "Unix socket to serve (SOCK_SEQPACKET)")->required();
  app.add_option("--scenario", scenario_name, "built-in scenario name or TOML file")->capture_default_str();
  app.add_flag("--once", once, "exit when the firmware disconnects");
  tnv::cli::add_version_flag(app, "tnv-board-emu");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return tnv::cli::report_parse_error(app, e, "tnv-board-emu", 2);
  }

  emu::ScenarioResult found = emu::resolve_scenario(scenario_name);
  if (!found.scenario) {
    std::fprintf(stderr, "tnv-board-emu: %s\n", found.error.empty() ? "no such scenario" : found.error.c_str());
    return 2;
  }
  emu::Machine machine(*found.scenario);
  board_emu::TickingBus bus(machine);

  const sigset_t stop_signals = drivers::block_stop_signals();
  const int stop_fd = signalfd(-1, &stop_signals, SFD_CLOEXEC);
  std::string error;
  const int listen_fd = drivers::listen_seqpacket(socket_path, error);
  if (listen_fd < 0) {
    std::fprintf(stderr, "tnv-board-emu: %s\n", error.c_str());
    return 1;
  }
  std::printf("tnv-board-emu: serving scenario '%s' on %s\n", found.scenario->name.c_str(), socket_path.c_str());
  std::fflush(stdout);

  int exit_code = 0;
  for (;;) {
    pollfd p[2] = {{listen_fd, POLLIN, 0}, {stop_fd, POLLIN, 0}};
    if (::poll(p, 2, -1) < 0) continue;
    if ((p[1].revents & POLLIN) != 0) {
      report(machine, bus.ticks_served(), "stopped");
      break;
    }
    const int fd = drivers::accept_seqpacket(listen_fd);
    if (fd < 0) continue;
    drivers::ServeStats stats;
    const drivers::ServeEnd end = drivers::serve_register_connection(fd, bus, stop_fd, stats);
    ::close(fd);
    if (end == drivers::ServeEnd::stopped) {
      report(machine, bus.ticks_served(), "stopped");
      break;
    }
    report(machine, bus.ticks_served(), end == drivers::ServeEnd::peer_closed ? "firmware disconnected" : "link error");
    if (stats.bad_requests > 0) {
      std::fprintf(stderr, "tnv-board-emu: %llu malformed requests answered with bus_error\n",
                   static_cast<unsigned long long>(stats.bad_requests));
    }
    if (once) {
      exit_code = end == drivers::ServeEnd::peer_closed ? 0 : 1;
      break;
    }
  }
  ::close(listen_fd);
  ::unlink(socket_path.c_str());
  return exit_code;
}
