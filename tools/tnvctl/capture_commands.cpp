// tnvctl capture: configure and arm the node's on-target capture, run a
// motion (--circle, --run "..."), wait for the recording, upload it with
// gap recovery, score a circle, write CSV and plot. --arm / --upload split
// the flow across invocations (the bench: arm, drive, then upload).
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <functional>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include "firmware/can/param_table.hpp"
#include "tools/cli/output_path.hpp"
#include "tools/cli/run_plotter.hpp"
#include "tools/can/capture_csv.hpp"
#include "tools/can/capture_run.hpp"
#include "tools/can/capture_score.hpp"
#include "tools/can/param_text.hpp"
#include "tools/score/score_json.hpp"
#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

namespace {

namespace can = fw::can;
using can_host::Micros;

struct CaptureOptions {
  std::string channels;  // "" = what the node has
  std::string trigger;   // "" = what the node has
  int decimation = 0;    // 0 = what the node has
  bool arm_only = false;
  bool upload_only = false;
  bool circle = false;
  std::optional<double> radius_mm;
  std::optional<double> feed_mm_s;
  std::string run;
  double wait_s = 60.0;
  double tail_s = 0.0;  // keep recording this long after the motion, then stop the capture
  std::string csv;
  std::string plot;
  std::string title;
  std::string label;
};

using can_host::capture_state_name;

// The motion to run after arming, parsed before anything is sent.
std::optional<Action> motion_action(const CaptureOptions& o) {
  std::vector<std::string> words;
  if (o.circle) {
    words.emplace_back("circle");
    char buf[40];
    if (o.radius_mm) {
      std::snprintf(buf, sizeof buf, "%.17g", *o.radius_mm);
      words.insert(words.end(), {"--radius-mm", buf});
    }
    if (o.feed_mm_s) {
      std::snprintf(buf, sizeof buf, "%.17g", *o.feed_mm_s);
      words.insert(words.end(), {"--feed-mm-s", buf});
    }
  } else if (!o.run.empty()) {
    std::string error;
    const auto split = split_words(o.run, error);
    if (!split) {
      std::string message = "--run: ";
      throw BadInput(message.append(error));
    }
    words = *split;
  } else {
    return std::nullopt;
  }
  static const char* kMotions[] = {"circle", "move", "jog", "stop"};
  if (words.empty() || std::find(std::begin(kMotions), std::end(kMotions), words.front()) == std::end(kMotions))
    throw BadInput("--run takes a motion command: circle, move or jog (e.g. --run \"move --axis x --distance-mm 5 --speed-mm-s 10\")");
  std::string error;
  std::optional<Action> action = parse_command_line(words, error);
  if (!action) {
    std::string message = "--run: ";
    throw BadInput(message.append(error));
  }
  return action;
}

void configure(const CaptureOptions& o, can_host::NodeClient& client, Report& report) {
  const can_host::ArmedCapture armed = can_host::arm_capture(client, {o.channels, o.trigger, o.decimation});
  std::string text = "capture ";
  text.append(capture_state_name(armed.status.state)).append(": ").append(can_host::channel_list_text(armed.channel_mask));
  text.append(", trigger ").append(armed.trigger).append(", every ").append(std::to_string(armed.decimation)).append(" tick(s)");
  report.line(text);
  report.data["channels"] = can_host::channel_list_text(armed.channel_mask);
  report.data["trigger"] = armed.trigger;
  report.data["decimation"] = armed.decimation;
}

void write_outputs(const CaptureOptions& o, const can_host::CaptureTable& table,
                   const std::optional<hil::ContourStats>& stats, Session& session, Report& report) {
  if (!o.csv.empty()) {
    if (!cli::write_file_replacing(o.csv, can_host::capture_csv(table))) {
      std::string message = o.csv;
      throw RunFailed(message.append(": cannot write"));
    }
    std::string text = "[csv] wrote ";
    report.line(text.append(o.csv));
    report.data["csv"] = o.csv;
  }
  if (!o.plot.empty()) {
    std::string title = o.title;
    if (title.empty()) {
      title = "capture, node ";
      title.append(std::to_string(session.options().node)).append(", ").append(session.client().bus().describe());
    }
    std::string label = o.label;
    if (label.empty()) label = stats ? "captured circle" : "capture";
    // Drawn from the CSV: --csv's file, or one kept beside the figure. The
    // plotter chooses the panels from what the capture is (a circle or not).
    const std::string csv = o.csv.empty() ? cli::plot_data_path(o.plot, ".plot.csv") : o.csv;
    if (o.csv.empty() && !cli::write_file_replacing(csv, can_host::capture_csv(table))) {
      std::string message = csv;
      throw RunFailed(message.append(": cannot write"));
    }
    const std::string error = cli::run_plotter("capture", {csv}, o.plot, {"--title", title, "--label", label});
    if (!error.empty()) throw RunFailed(error);
    std::string text = "[plot] wrote ";
    report.line(text.append(o.plot));
    report.data["plot"] = o.plot;
  }
}

// Upload progress on stderr, once the upload has taken a second of wall
// time (on a real bus a long capture takes several; emulated ones rarely one).
class UploadProgressLine {
 public:
  void operator()(std::uint64_t done, std::uint64_t total) {
    const auto now = std::chrono::steady_clock::now();
    if (!started_) {
      started_ = true;
      start_ = now;
    }
    if (now - start_ < std::chrono::seconds(1) && !shown_) return;
    shown_ = true;
    const int pct = total == 0 ? 100 : static_cast<int>(100 * done / total);
    if (isatty(STDERR_FILENO) != 0) {
      std::fprintf(stderr, "\r[capture] upload %3d%%", pct);
      if (done >= total) std::fputc('\n', stderr);
    } else if (pct / 25 != last_ / 25 || done >= total) {
      std::fprintf(stderr, "[capture] upload %d%%\n", pct);
    }
    last_ = pct;
    std::fflush(stderr);
  }

 private:
  bool started_ = false;
  bool shown_ = false;
  int last_ = -1;
  std::chrono::steady_clock::time_point start_{};
};

// Everything checked before anything is sent; returns the motion to run.
std::optional<Action> check_capture(const CaptureOptions& o) {
  if (o.arm_only && o.upload_only) throw BadInput("--arm and --upload exclude each other");
  if ((o.arm_only || o.upload_only) && (o.circle || !o.run.empty()))
    throw BadInput("--circle / --run run between arming and uploading: not with --arm or --upload");
  if (o.circle && !o.run.empty()) throw BadInput("--circle and --run exclude each other");
  if ((o.radius_mm || o.feed_mm_s) && !o.circle) throw BadInput("--radius-mm / --feed-mm-s go with --circle");
  if (o.arm_only && (!o.csv.empty() || !o.plot.empty())) throw BadInput("--csv / --plot need an upload, not --arm");
  try {
    can_host::check_capture_setup({o.channels, o.trigger, o.decimation});
  } catch (const std::invalid_argument& e) {
    throw BadInput(e.what());
  }
  if (!(o.wait_s >= 0.0 && std::isfinite(o.wait_s))) throw BadInput("--wait-s must be >= 0");
  if (!(o.tail_s >= 0.0 && o.tail_s <= 3600.0)) throw BadInput("--tail-s must be in [0, 3600]");
  if (o.tail_s > 0.0 && (o.arm_only || o.upload_only)) throw BadInput("--tail-s goes with a recording run here");
  std::optional<Action> motion = motion_action(o);
  if (motion && motion->check) motion->check();
  return motion;
}

int run_capture(const CaptureOptions& o, Session& session, Report& report) {
  const std::optional<Action> motion = check_capture(o);
  can_host::NodeClient& client = session.client();
  if (!o.upload_only) {
    configure(o, client, report);
    if (o.arm_only) return kExitOk;
    if (motion) {
      Report motion_report(report.json_mode());
      const int code = motion->run(session, motion_report);
      report.data["motion"] = motion_report.data;
      if (code != kExitOk) return code;
    }
    // What follows the motion (settling), then stop: the recording keeps what it has.
    if (o.tail_s > 0.0) can_host::stop_capture_after(client, Micros{static_cast<long long>(o.tail_s * 1e6)});
  }
  UploadProgressLine progress;
  const can_host::DownloadedCapture d =
      can_host::download_capture(client, Micros{static_cast<long long>(o.wait_s * 1e6)}, std::ref(progress));
  const can_host::CaptureTable* table = &d.table;
  const can_host::CaptureStatus& status = d.status;
  const can::ChannelMask mask = d.channel_mask;
  const double upload_s = d.upload_s;
  char buf[200];
  std::snprintf(buf, sizeof buf, "captured %u samples x %u channels (%.3f s), %zu bytes uploaded in %.2f s, %llu re-requests",
                status.samples, status.channels, status.samples * status.decimation * 1e-3, d.bytes, upload_s,
                static_cast<unsigned long long>(d.rerequests));
  report.line(buf);
  report.data["samples"] = status.samples;
  report.data["channels"] = can_host::channel_list_text(mask);
  report.data["decimation"] = status.decimation;
  report.data["bytes"] = d.bytes;
  report.data["upload_s"] = upload_s;
  report.data["rerequests"] = d.rerequests;

  std::string score_error;
  const std::optional<hil::ContourStats> stats = can_host::score_circle(*table, score_error);
  if (stats) {
    std::snprintf(buf, sizeof buf, "contour error: max %.4f um   mean %.4f um   std %.4f um   (%zu samples in motion)",
                  stats->max_um, stats->mean_um, stats->std_um, stats->samples);
    report.line(buf);
    report.data["circle"] = hil::contour_stats_json(*stats);
  }
  write_outputs(o, *table, stats, session, report);
  return kExitOk;
}

}  // namespace

void add_capture_commands(CLI::App& app, ActionSlot& slot) {
  auto o = std::make_shared<CaptureOptions>();
  CLI::App* cmd = app.add_subcommand(
      "capture",
      "on-target capture at full tick rate: arm, run (--circle / --run), wait, upload, score, write CSV / plot");
  cmd->add_option("--channels", o->channels,
                  "comma-separated channel names, 'default' or 'all' (default: the node's capture.channels)");
  cmd->add_option("--trigger", o->trigger, "immediate | motion | fault (default: the node's capture.trigger)")
      ->check(CLI::IsMember({"immediate", "motion", "fault"}));
  cmd->add_option("--decimation", o->decimation, "ticks per sample (default: the node's)")->check(CLI::Range(1, 255));
  cmd->add_flag("--arm", o->arm_only, "only configure and arm (upload later with --upload)");
  cmd->add_flag("--upload", o->upload_only, "only upload the last recording");
  cmd->add_flag("--circle", o->circle, "run the circle after arming");
  cmd->add_option("--radius-mm", o->radius_mm, "with --circle: mm");
  cmd->add_option("--feed-mm-s", o->feed_mm_s, "with --circle: mm/s");
  cmd->add_option("--run", o->run, "a motion command to run after arming, e.g. \"move --axis x --distance-mm 5 --speed-mm-s 10\"");
  cmd->add_option("--wait-s", o->wait_s, "longest wait for the recording to finish")->capture_default_str();
  cmd->add_option("--tail-s", o->tail_s,
                  "keep recording this long after the motion, then stop (with --trigger immediate: the settling)");
  cmd->add_option("--csv", o->csv, "write the samples (CSV)")->check(tnv::cli::OutputFile());
  cmd->add_option("--plot", o->plot, "write the plot (.svg, .png or .pdf)")->check(tnv::cli::PlotFile());
  cmd->add_option("--title", o->title, "plot title");
  cmd->add_option("--label", o->label, "plot row label");
  cmd->callback([&slot, o] {
    slot = Action{"capture", true, [o](Session& s, Report& r) { return run_capture(*o, s, r); },
                  [o] { check_capture(*o); }};
  });
}

}  // namespace tnv::tnvctl
