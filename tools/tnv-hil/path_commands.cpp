// tnv-hil path FILE.ngc: a G-code program on the emulated table, scored
// against its exact programmed geometry (docs/motion.md).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "tools/cli/gcode_setup_options.hpp"
#include "tools/cli/output_path.hpp"
#include "tools/cli/run_plotter.hpp"
#include "tools/gcode/gcode_program.hpp"
#include "tools/hil/best_circle.hpp"
#include "tools/hil/path_csv.hpp"
#include "tools/hil/path_run.hpp"
#include "tools/hil/report.hpp"
#include "tools/score/score_json.hpp"
#include "tools/tnv-hil/cli_support.hpp"
#include "tools/tnv-hil/commands.hpp"

namespace tnv::cli {

namespace {

struct PathOptions {
  std::string file;
  GcodeSetupOptions files;  // --tool-table, --var-file, --subroutine-path
  FromLineOptions from;     // --from-line and its companions
  FeedHoldOptions holds;    // --hold-at, --resume-at
  std::string controller = "rdvsc";
  std::string scenario = "no-cut";
  int seeds = 1;
  bool best = false;
  double rapid_feed_mm_s = 50.0;
  double resume_after_s = 1.0;
  bool json = false;
  std::string plot;
  std::string csv;
};

int run_path_command(const PathOptions& o) {
  const auto kind = controller_or_report(o.controller);
  const auto scenario = resolve_scenario_or_report(o.scenario);
  if (!kind || !scenario) return kExitBadInput;
  std::string text;
  std::string error;
  if (!gcode::read_program_file(o.file, text, error)) {
    std::fprintf(stderr, "tnv-hil path: %s\n", error.c_str());
    return kExitBadInput;
  }
  fw::FirmwareConfig config = fw::default_firmware_config();
  if (o.best) {
    // The best configuration of tnv-hil best-circle, designed on this table.
    const hil::BestConfigDesign d = hil::design_best_config(*scenario, {});
    if (!d.ok) {
      std::fprintf(stderr, "tnv-hil path: --best: %s\n", d.error.c_str());
      return d.bad_input ? kExitBadInput : kExitFailure;
    }
    config = d.config;
  }
  hil::PathRunOptions options;
  if (!load_gcode_setup(o.files, options.canon, error)) {
    std::fprintf(stderr, "tnv-hil path: %s\n", error.c_str());
    return kExitBadInput;
  }
  apply_from_line(o.from, options.canon);
  gcode::add_program_directory(options.canon, o.file);
  error = gcode::feed_hold_windows(o.holds.hold_at_s, o.holds.resume_at_s, options.feed_holds);
  if (!error.empty()) {
    std::fprintf(stderr, "tnv-hil path: %s\n", error.c_str());
    return kExitBadInput;
  }
  options.rapid_feed_mm_s = o.rapid_feed_mm_s;
  options.resume_after_s = o.resume_after_s;
  options.keep_samples = !o.plot.empty() || !o.csv.empty();
  Progress progress("path");
  const hil::PathSweepResult r =
      hil::run_path_seeds(*scenario, config, *kind, text, o.seeds, options,
                          o.seeds > 1 ? std::function<void(std::size_t, std::size_t)>(std::ref(progress)) : nullptr);
  const hil::PathRunResult& seed0 = r.per_seed.front();
  // A G-code error is the input's fault, found before anything moved.
  if (!seed0.completed && seed0.segments == 0 && seed0.counters.ticks < 10) {
    std::fprintf(stderr, "tnv-hil path: %s: %s\n", o.file.c_str(), seed0.error.c_str());
    return kExitBadInput;
  }
  if (o.json) {
    nlohmann::json j = hil::path_score_json(r.mean);
    j.update(hil::program_summary_json(seed0.program));
    j["file"] = o.file;
    j["controller"] = o.controller;
    j["scenario"] = scenario->name;
    j["seeds"] = o.seeds;
    j["best"] = o.best;
    j["underruns"] = r.underruns;
    // Judged from the machine (tools/hil/feed_start_judge.hpp); summed over seeds. A crash fails the run.
    j["crashes"] = r.crashes;
    j["feed_before_at_speed"] = r.feed_before_at_speed;
    j["feed_onsets"] = seed0.feed_onsets;
    j["tool_force_max_n"] = seed0.tool_force_max_n;
    j["programmed_length_mm"] = seed0.programmed_length_mm;
    j["segments"] = seed0.segments;
    nlohmann::json per_seed = nlohmann::json::array();
    for (const hil::PathRunResult& s : r.per_seed) {
      nlohmann::json e = hil::path_score_json(s.score);
      e["crashes"] = s.crashes;
      e["feed_before_at_speed"] = s.feed_before_at_speed;
      per_seed.push_back(e);
    }
    j["per_seed"] = per_seed;
    nlohmann::json pauses = nlohmann::json::array();
    for (const hil::PathPause& p : seed0.pauses) {
      nlohmann::json pj{{"line", p.line}, {"reason", gcode::to_string(p.why.reason)}, {"paused_s", p.paused_s}};
      if (p.why.reason == gcode::PauseReason::tool_change) pj["tool"] = p.why.tool;
      pauses.push_back(pj);
    }
    j["pauses"] = pauses;
    nlohmann::json holds = nlohmann::json::array();
    for (const hil::PathHold& h : seed0.holds) {
      holds.push_back({{"hold_at_s", h.window.hold_at_s},
                       {"resume_at_s", h.window.resume_at_s},
                       {"applied", h.applied},
                       {"path_speed_at_hold_mm_s", h.path_speed_at_hold_mm_s},
                       {"stopped_after_s", h.stopped_after_s},
                       {"spindle_rpm_min_held", h.spindle_rpm_min_held},
                       {"spindle_rpm_max_held", h.spindle_rpm_max_held}});
    }
    j["holds"] = holds;
    j["held_s"] = seed0.held_s;
    j["error"] = r.error;
    note_io_work_unmetered(j, *scenario);
    std::cout << j.dump(2) << '\n';
  } else {
    const hil::PathScore& m = r.mean;
    std::printf("path %s: %llu segments, %.1f mm, %s%s on %s, %d seed%s\n", o.file.c_str(),
                static_cast<unsigned long long>(seed0.segments), seed0.programmed_length_mm, o.controller.c_str(),
                o.best ? " (best configuration)" : "", scenario->name.c_str(), o.seeds, o.seeds == 1 ? "" : "s");
    std::printf("contour error (um)     max %.4f  mean %.4f  std %.4f%s\n", m.contour_error_max_um,
                m.contour_error_mean_um, m.contour_error_std_um, o.seeds > 1 ? "   (seed average)" : "");
    std::printf("path deviation (um)    max %.4f   (the planner's reference against the program)\n",
                m.path_deviation_max_um);
    std::printf("accel ratio max %.4f  jerk ratio max %.4f   (commanded / limit, worst axis)\n", m.accel_ratio_max,
                m.jerk_ratio_max);
    std::printf("feed ratio %.4f  cycle time %.3f s  underruns %llu\n", m.feed_ratio, m.cycle_time_s,
                static_cast<unsigned long long>(r.underruns));
    std::printf("program: %s\n", gcode::summary_text(seed0.program).c_str());
    std::printf("crashes %llu  feed moves before the spindle was at speed %u (of %u feed starts%s)%s\n",
                static_cast<unsigned long long>(r.crashes), r.feed_before_at_speed, seed0.feed_onsets,
                o.seeds > 1 ? " in seed 0; counts summed over seeds" : "",
                scenario->stock.enabled ? "" : "   (no [stock]: nothing to crash into)");
    if (scenario->stock.enabled) std::printf("milling force where the tool is: max %.1f N (seed 0)\n", seed0.tool_force_max_n);
    for (const hil::PathPause& p : seed0.pauses) {
      std::printf("paused at line %d: %s; continued after %.3f s (not scored)\n", p.line, gcode::to_string(p.why).c_str(),
                  p.paused_s);
    }
    for (const hil::PathHold& h : seed0.holds) {
      if (!h.applied) {
        std::printf("feed hold at %.3f s: not applied, the program had ended\n", h.window.hold_at_s);
        continue;
      }
      std::printf("feed hold %.3f-%.3f s: path speed %.3f mm/s at the hold, at rest after %.3f s, spindle %.0f-%.0f "
                  "rpm while held (scored)\n",
                  h.window.hold_at_s, h.window.resume_at_s, h.path_speed_at_hold_mm_s, h.stopped_after_s,
                  h.spindle_rpm_min_held, h.spindle_rpm_max_held);
    }
  }
  bool ok = r.error.empty();
  if (!ok) std::fprintf(stderr, "tnv-hil path: %s\n", r.error.c_str());
  if ((!o.plot.empty() || !o.csv.empty()) && !seed0.samples.empty()) {
    const std::string title = "tnv-hil path " + std::filesystem::path(o.file).filename().string() + ", " +
                              o.controller + ", " + scenario->name + " (seed 0)";
    // The figure is drawn from the CSV: --csv's file, or one kept beside the figure.
    const std::string csv = o.csv.empty() ? plot_data_path(o.plot, ".plot.csv") : o.csv;
    const bool csv_written = write_text(csv, hil::path_csv(seed0.program, seed0));
    ok = csv_written && ok;
    if (csv_written && !o.plot.empty()) {
      const hil::PathScore& s = seed0.score;
      char score[200];
      std::snprintf(score, sizeof score, "\ncontour error max %.3f um, mean %.3f um; feed ratio %.3f, cycle %.2f s",
                    s.contour_error_max_um, s.contour_error_mean_um, s.feed_ratio, s.cycle_time_s);
      ok = plot_files(o.plot, "path", {csv}, {"--title", title + score}, "tnv-hil") && ok;
    }
  }
  return ok ? kExitOk : kExitFailure;
}

}  // namespace

void add_path_commands(CLI::App& app, Runner& run) {
  auto o = std::make_shared<PathOptions>();
  CLI::App* cmd = app.add_subcommand(
      "path", "run a G-code program (LinuxCNC's RS274/NGC dialect, X, Y and Z) on the emulated machine and score it against "
              "its geometry");
  cmd->add_option("file", o->file, "the program (.ngc)")->required();
  add_gcode_setup_options(*cmd, o->files);
  add_from_line_options(*cmd, o->from);
  add_feed_hold_options(*cmd, o->holds);
  cmd->add_option("--controller", o->controller, "pid | dvsc | rdvsc")
      ->check(CLI::IsMember({"pid", "dvsc", "rdvsc"}))
      ->capture_default_str();
  cmd->add_option("--scenario", o->scenario, "built-in name or TOML file")->capture_default_str();
  cmd->add_option("--seeds", o->seeds, "average over N encoder offsets / cutting phases")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_flag("--best", o->best,
                "the best configuration of tnv-hil best-circle (gains designed from this table, friction "
                "feed-forward, speed observer)");
  cmd->add_option("--rapid-feed", o->rapid_feed_mm_s, "G0 path speed, mm/s")
      ->check(CLI::Range(0.01, 1000.0))
      ->capture_default_str();
  cmd->add_option("--resume-after-s", o->resume_after_s,
                  "a program pause (M0, M1 with --optional-stop on, M6) continues after resting this long; the "
                  "pause's ticks are not scored")
      ->check(CLI::Range(0.0, 600.0))
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "print JSON on stdout");
  cmd->add_option("--plot", o->plot, "write the path, contour-error and path-speed figure (.svg, .png or .pdf)")->check(tnv::cli::OutputFile());
  cmd->add_option("--csv", o->csv, "write seed 0's ticks: reference, position, contour error, path speed (CSV)")->check(tnv::cli::OutputFile());
  cmd->callback([&run, o] { run = [o] { return run_path_command(*o); }; });
}

}  // namespace tnv::cli
