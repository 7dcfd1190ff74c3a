// tnv-fw: the TNV-40 firmware on a Linux board (docs/install-board.md).
//   tnv-fw --config FILE                    run until SIGTERM / SIGINT
//   tnv-fw --config FILE --check-config     validate the file and exit
//   tnv-fw --config FILE --check-config --probe   ... and open its devices
//   tnv-fw --config FILE --can IFACE        use IFACE, not can.interface
//   tnv-fw [--config FILE] --latency-test S wake-up latency histogram
// Exit codes: 0 clean stop, 1 a device could not be opened or the
// real-time policy was refused, 2 bad command line or config file.
#include <signal.h>
#include <time.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

#include "drivers/linux/stop_signals.hpp"
#include "tools/cli/cli_frame.hpp"
#include "tools/tnv-fw/config_probe.hpp"
#include "tools/tnv-fw/daemon.hpp"
#include "tools/tnv-fw/fw_config.hpp"
#include "tools/tnv-fw/latency_test.hpp"

namespace {

using namespace tnv;

int run(const fwd::DaemonConfig& config, const fwd::DaemonOptions& options) {
  const sigset_t stop_signals = drivers::block_stop_signals();  // the loop thread inherits the mask
  std::string error;
  std::unique_ptr<fwd::Daemon> daemon = fwd::Daemon::open(config, options, error);
  if (!daemon) {
    std::fprintf(stderr, "tnv-fw: %s\n", error.c_str());
    return 1;
  }
  if (const std::string e = daemon->start(); !e.empty()) {
    std::fprintf(stderr, "tnv-fw: %s\n", e.c_str());
    daemon->stop();
    return 1;
  }
  if (!daemon->warnings().empty()) std::fprintf(stderr, "tnv-fw: WARNING: %s\n", daemon->warnings().c_str());
  std::fprintf(stderr, "tnv-fw: running (board %s, CAN %s node %u, tick %u us)\n", config.board.path.c_str(),
               config.can.interface_name.c_str(), static_cast<unsigned>(config.can.node_id), config.tick.period_us);
  const char* why = "loop ended";
  for (;;) {
    const timespec wait{0, 100'000'000};
    const int sig = sigtimedwait(&stop_signals, nullptr, &wait);
    if (sig == SIGTERM || sig == SIGINT) {
      why = sig == SIGTERM ? "SIGTERM" : "SIGINT";
      break;
    }
    if (daemon->finished()) break;
  }
  const fwd::SafeStateReport safe = daemon->stop();
  std::fprintf(stderr, "tnv-fw: stopped (%s); %s\n%s\n", why, safe.one_line().c_str(), daemon->summary().c_str());
  return safe.safe ? 0 : 1;
}

// --check-config --probe: one line per device on stdout, each failure
// also on stderr naming the key, the device and the error; exit 1 when any
// could not be opened (as the daemon's start would fail).
int probe(const std::string& config_path, const fwd::DaemonConfig& config) {
  const fwd::ProbeReport report = fwd::probe_devices(config);
  std::size_t opened = 0;
  for (const fwd::ProbeItem& item : report.items) {
    if (!item.probed) {
      std::printf("  skipped  %s (%s)\n", item.what.c_str(), item.detail.c_str());
    } else if (item.ok) {
      ++opened;
      std::printf("  ok       %s\n", item.what.c_str());
    } else {
      std::printf("  FAILED   %s: %s\n", item.what.c_str(), item.detail.c_str());
      std::fprintf(stderr, "tnv-fw: %s: %s: %s\n", config_path.c_str(), item.what.c_str(), item.detail.c_str());
    }
  }
  std::fflush(stdout);
  if (!report.ok()) {
    std::fprintf(stderr, "tnv-fw: %s: probe failed: %zu of %zu devices could not be opened\n", config_path.c_str(),
                 report.failures(), report.failures() + opened);
    return 1;
  }
  std::printf("%s: ok (%zu devices opened)\n", config_path.c_str(), opened);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"TNV-40 firmware for a Linux board"};
  std::string config_path;
  double latency_seconds = 0.0;
  bool check_only = false;
  bool probe_flag = false;
  std::string can_interface;
  std::uint64_t max_ticks = 0;
  app.add_option("--config", config_path, "TOML configuration file");
  app.add_option("--latency-test", latency_seconds, "measure the wake-up latency for SECONDS and print a histogram")
      ->check(CLI::Range(0.01, 86400.0));
  CLI::Option* check_flag = app.add_flag("--check-config", check_only, "validate the config file and exit");
  app.add_flag("--probe", probe_flag,
               "with --check-config: also open the configured spidev device, GPIO lines and CAN interface")
      ->needs(check_flag);
  app.add_option("--can", can_interface, "CAN interface to use instead of the config's can.interface (tnv-fw@IFACE)");
  app.add_option("--ticks", max_ticks, "stop after this many ticks (tests)");
  tnv::cli::add_version_flag(app, "tnv-fw");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return tnv::cli::report_parse_error(app, e, "tnv-fw", 2);
  }

  fwd::DaemonConfig config;
  if (!config_path.empty()) {
    fwd::ConfigResult loaded = fwd::load_daemon_config(config_path);
    if (!loaded.config) {
      std::fprintf(stderr, "tnv-fw: %s\n", loaded.error.c_str());
      return 2;
    }
    config = *loaded.config;
  }
  if (!can_interface.empty()) {
    if (can_interface.rfind("unix:", 0) != 0 && can_interface.size() > 15) {
      std::fprintf(stderr, "tnv-fw: --can %s: a network interface name has at most 15 characters\n",
                   can_interface.c_str());
      return 2;
    }
    config.can.interface_name = can_interface;
  }
  if (latency_seconds > 0.0) {
    // Without a config file the test measures whatever the policy gets (and says so).
    if (config_path.empty()) config.rt.require = false;
    return fwd::run_latency_test(config.rt, config.tick.period_us, latency_seconds, stdout, stderr);
  }
  if (config_path.empty()) {
    std::fprintf(stderr, "tnv-fw: --config FILE is required (or --latency-test SECONDS)\n");
    return 2;
  }
  if (const std::string why = fwd::daemon_run_error(config); !why.empty()) {
    std::fprintf(stderr, "tnv-fw: %s: %s\n", config_path.c_str(), why.c_str());
    return 2;
  }
  if (check_only) {
    if (probe_flag) return probe(config_path, config);
    std::printf("%s: ok\n", config_path.c_str());
    return 0;
  }
  fwd::DaemonOptions options;
  options.max_ticks = max_ticks;
  return run(config, options);
}
