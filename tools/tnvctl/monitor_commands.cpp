// tnvctl monitor: live status from the heartbeat and the cyclic telemetry.
#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>

#include "firmware/can/param_table.hpp"
#include "hal/axis.hpp"
#include "tools/can/telemetry_csv.hpp"
#include "tools/can/telemetry_view.hpp"
#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

namespace {

namespace can = fw::can;
using can::MessageId;
using can_host::Micros;

std::atomic<bool> g_interrupted{false};
extern "C" void on_interrupt(int) { g_interrupted = true; }

struct MonitorOptions {
  double duration_s = 0.0;  // 0: until Ctrl-C
  double rate_hz = 10.0;
  bool csv = false;  // CSV rows on stdout (header first), summary on stderr
};

std::string sample_text(const can_host::TelemetryView& l, double t_s) {
  char buf[480];
  int n = std::snprintf(buf, sizeof buf, "t %7.2f s  %-8s %-10s", t_s,
                        l.heartbeat ? fw::to_string(l.heartbeat->state) : "?",
                        l.heartbeat ? fw::to_string(l.heartbeat->fault) : "?");
  auto room = [&] { return sizeof buf - static_cast<std::size_t>(std::min<int>(n, sizeof buf - 1)); };
  // Per axis, from the axis list: "  x 1.000000 y 2.000000 mm".
  if (l.position_mm) {
    for (const hal::Axis a : hal::kAxes)
      n += std::snprintf(buf + n, room(), "%s%s %10.6f", a == hal::kAxes[0] ? "  " : " ", hal::axis_label(a),
                         (*l.position_mm)[hal::index(a)]);
    n += std::snprintf(buf + n, room(), " mm");
  }
  if (l.following_mm) {
    n += std::snprintf(buf + n, room(), "  following");
    for (const hal::Axis a : hal::kAxes)
      n += std::snprintf(buf + n, room(), " %s %8.2f", hal::axis_label(a), (*l.following_mm)[hal::index(a)] * 1e3);
    n += std::snprintf(buf + n, room(), " um");
  }
  if (l.contour) n += std::snprintf(buf + n, room(), "  contour %7.3f um", l.contour->contour_um);
  if (l.s_mm_s) {
    n += std::snprintf(buf + n, room(), "  s");
    for (const double v : *l.s_mm_s) n += std::snprintf(buf + n, room(), " %8.4f", v);
  }
  if (l.output) {
    n += std::snprintf(buf + n, room(), "  dac");
    for (const double v : l.output->dac_code) n += std::snprintf(buf + n, room(), " %5.0f", v);
    n += std::snprintf(buf + n, room(), "  force %7.2f N", l.output->force_n);
  }
  if (l.arsc)
    n += std::snprintf(buf + n, room(), "  force %7.2f / %7.2f N  override %5.3f  G %6.3f N*s/mm", l.arsc->force_n,
                       l.arsc->force_ref_n, l.arsc->feed_override, l.arsc->cutting_gain_n_per_mm_s);
  if (l.spindle)
    n += std::snprintf(buf + n, room(), "  spindle %s %6.0f / %6.0f rpm", can_host::spindle_state(*l.spindle),
                       l.spindle->measured_rpm, l.spindle->command_rpm);
  if (l.program_tool) n += std::snprintf(buf + n, room(), "  in spindle: %s", can_host::to_string(*l.program_tool).c_str());
  return buf;
}

void check_monitor(const MonitorOptions& o, bool json) {
  if (o.csv && json) throw BadInput("--csv and --json both format stdout: give one");
  if (!(o.rate_hz > 0.0 && o.rate_hz <= 1000.0)) throw BadInput("--rate-hz must be in (0, 1000]");
  if (!(o.duration_s >= 0.0 && o.duration_s <= 1e6)) throw BadInput("--duration-s must be in [0, 1e6]");
}

int run_monitor(const MonitorOptions& o, Session& session, Report& report) {
  check_monitor(o, report.json_mode());
  // stdout carries the samples alone (JSON Lines or CSV rows): the summary goes to stderr.
  if (report.json_mode() || o.csv) report.summary_to_stderr();
  can_host::NodeClient& client = session.client();
  const double bitrate_bit_s = client.get(*can::find_param("can.bitrate_kbit")) * 1000.0;
  can_host::EmulatedBus* emu = session.emulated();
  can_host::TelemetryView latest;
  client.set_listener([&latest](const hal::CanFrame& f, MessageId id) { latest.take(f, id); });
  g_interrupted = false;
  auto previous = std::signal(SIGINT, on_interrupt);
  if (emu != nullptr) emu->set_realtime(true);  // simulated time at wall-clock pace: it looks live
  const Micros start = client.bus().now();
  const Micros period{static_cast<long long>(1e6 / o.rate_hz)};
  const Micros end = o.duration_s > 0.0 ? start + Micros{static_cast<long long>(o.duration_s * 1e6)} : Micros::max();
  std::uint64_t lines = 0;
  if (o.csv) std::cout << can_host::telemetry_csv_header() << '\n';
  // The tool in the spindle comes with PROGRAM_STATUS: asked for once a second (COMMAND program_status is
  // open to every host), so a restarted node's "unknown" shows within a second, not a stale tool.
  const Micros ask_tool_every{1'000'000};
  Micros tool_asked = start - ask_tool_every;
  try {
    for (Micros next = start + period; !g_interrupted && client.bus().now() < end; next += period) {
      if (client.bus().now() - tool_asked >= ask_tool_every) {
        tool_asked = client.bus().now();
        client.command(can::CommandCode::program_status);
      }
      const Micros wait = std::min(next, end) - client.bus().now();
      if (wait > Micros{0}) client.pump(wait);
      const double t_s = static_cast<double>((client.bus().now() - start).count()) * 1e-6;
      const double load = t_s > 0.0 ? static_cast<double>(latest.bits) / (t_s * bitrate_bit_s) : 0.0;
      if (report.json_mode()) std::cout << can_host::telemetry_json(latest, t_s, load).dump() << '\n';
      else if (o.csv) std::cout << can_host::telemetry_csv_row(latest, t_s, load) << '\n';
      else std::cout << sample_text(latest, t_s) << '\n';
      std::cout.flush();
      ++lines;
    }
  } catch (...) {
    if (emu != nullptr) emu->set_realtime(false);
    std::signal(SIGINT, previous);
    client.set_listener({});
    throw;
  }
  if (emu != nullptr) emu->set_realtime(false);
  std::signal(SIGINT, previous);
  client.set_listener({});
  const double t_s = static_cast<double>((client.bus().now() - start).count()) * 1e-6;
  const double frames_per_s = t_s > 0.0 ? static_cast<double>(latest.frames) / t_s : 0.0;
  const double load = t_s > 0.0 ? static_cast<double>(latest.bits) / (t_s * bitrate_bit_s) : 0.0;
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "%.2f s: %llu frames from node %d (%.1f frames/s), %.2f%% of %.0f kbit/s (nominal frame bits, no "
                "stuffing)",
                t_s, static_cast<unsigned long long>(latest.frames), client.node(), frames_per_s, load * 100.0,
                bitrate_bit_s / 1000.0);
  report.line(buf);
  report.data["duration_s"] = t_s;
  report.data["frames"] = latest.frames;
  report.data["frames_per_s"] = frames_per_s;
  report.data["bus_load"] = load;
  report.data["lines"] = lines;
  return kExitOk;
}

}  // namespace

void add_monitor_commands(CLI::App& app, ActionSlot& slot) {
  auto o = std::make_shared<MonitorOptions>();
  CLI::App* cmd = app.add_subcommand(
      "monitor", "live status from the heartbeat and telemetry (emulated: paced to the wall clock); Ctrl-C ends");
  cmd->add_option("--duration-s", o->duration_s, "seconds; 0 = until Ctrl-C")->capture_default_str();
  cmd->add_option("--rate-hz", o->rate_hz, "status lines per second")->capture_default_str();
  cmd->add_flag("--csv", o->csv, "CSV on stdout: a header, then one row per sample (summary on stderr)");
  cmd->callback([&slot, o] {
    slot = Action{"monitor", true, [o](Session& s, Report& r) { return run_monitor(*o, s, r); },
                  [o] { check_monitor(*o, false); }};
  });
}

}  // namespace tnv::tnvctl
