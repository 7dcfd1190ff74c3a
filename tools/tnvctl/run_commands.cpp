// tnvctl run FILE.ngc: stream a G-code program to the node and score the
// run (the work is in tools/can/program_run.hpp; this file parses and prints).
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tools/can/operator_console.hpp"
#include "tools/can/program_run.hpp"
#include "tools/can_emu/cut_watch.hpp"
#include "tools/can_emu/emulated_bus.hpp"
#include "tools/cli/gcode_setup_options.hpp"
#include "tools/gcode/probe_outcome.hpp"
#include "tools/score/score_json.hpp"
#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

namespace {

std::atomic<bool> g_run_interrupted{false};
extern "C" void on_run_interrupt(int) { g_run_interrupted = true; }

struct RunOptions {
  std::string file;
  cli::GcodeSetupOptions files;  // --tool-table, --var-file, --subroutine-path
  cli::FromLineOptions from;     // --from-line and its companions
  cli::FeedHoldOptions holds;    // --hold-at, --resume-at
  std::optional<double> feed_override;
  double rapid_feed_mm_s = 50.0;
  bool no_score = false;
  int window = 12;
  // Program pauses (M0, M1, M6) continue after this long by themselves; unset: the operator presses Enter.
  std::optional<double> resume_after_s;
};

std::string read_file(const std::string& path) {
  std::string text;
  std::string error;
  if (!gcode::read_program_file(path, text, error)) throw BadInput(error);
  return text;
}

// The tool table, parameters and subroutine path the program runs with;
// subroutine files are looked for beside the program first.
gcode::CanonSetup run_setup(const RunOptions& o) {
  gcode::CanonSetup setup;
  std::string error;
  if (!cli::load_gcode_setup(o.files, setup, error)) throw BadInput(error);
  cli::apply_from_line(o.from, setup);
  gcode::add_program_directory(setup, o.file);
  return setup;
}

// The --hold-at / --resume-at schedule, or the reason it is refused.
std::vector<gcode::FeedHoldWindow> hold_schedule(const RunOptions& o) {
  std::vector<gcode::FeedHoldWindow> windows;
  if (const std::string error = gcode::feed_hold_windows(o.holds.hold_at_s, o.holds.resume_at_s, windows);
      !error.empty())
    throw BadInput(error);
  return windows;
}

// The program read as from any start point and on any table: the limits
// are wide open (the node's own come with the run), probes read as if none
// tripped.
gcode::GcodeResult read_anywhere(const RunOptions& o, const gcode::CanonSetup& setup) {
  gcode::GcodeOptions g;
  g.rapid_feed_mm_s = o.rapid_feed_mm_s;
  g.canon = setup;
  g.run_probe = gcode::untouched_probe;  // read as if no probe tripped: the run reads on from each result
  for (fw::motion::AxisLimits& a : g.limits.axis) {
    a.speed_mm_s = 1e9;
    a.position_min_mm = -1e9;
    a.position_max_mm = 1e9;
  }
  return gcode::parse_gcode(read_file(o.file), g);
}

// Before anything is sent and before the bus is opened: the options, and the
// program's syntax, so only what is wrong from any start point and on any
// table is reported now. The program as read, for check_pauses.
gcode::GcodeProgram check_run(const RunOptions& o) {
  if (o.feed_override && !(*o.feed_override >= 0.0 && *o.feed_override <= 1.5))
    throw BadInput("--feed-override must be in [0, 1.5]");
  if (!(o.rapid_feed_mm_s > 0.0 && o.rapid_feed_mm_s <= 655.35)) throw BadInput("--rapid-feed must be in (0, 655.35] mm/s");
  gcode::GcodeResult r = read_anywhere(o, run_setup(o));
  if (r.error) throw BadInput(o.file + ": " + gcode::to_string(*r.error) + " (nothing was sent)");
  if (r.program.segments.empty()) throw BadInput(o.file + ": the program has no motion and no dwell (nothing was sent)");
  if (o.resume_after_s && !(*o.resume_after_s >= 0.0 && *o.resume_after_s <= 3600.0))
    throw BadInput("--resume-after-s must be in [0, 3600] s");
  hold_schedule(o);
  return std::move(r.program);
}

// A pause waits for the operator's Enter: without a terminal nobody could
// press it. `program` is read with the tool in the spindle the run starts
// with; `tool_unknown`: nobody said which (no --tool-in-spindle, and the
// node does not know), so a run from line changes to its tool first.
void check_pauses(const RunOptions& o, const gcode::GcodeProgram& program, bool tool_unknown) {
  if (program.pauses.empty() || o.resume_after_s || isatty(STDIN_FILENO) != 0) return;
  const auto line_of = [&program](const gcode::ProgramPause& p) { return std::to_string(program.segments[p.segment].tag); };
  const gcode::ProgramPause& p = program.pauses.front();
  std::string tool_change;  // a manual tool change nobody could confirm, named even when another pause comes first
  const auto m6 = std::find_if(program.pauses.begin(), program.pauses.end(), [](const gcode::ProgramPause& q) {
    return q.reason == gcode::PauseReason::tool_change;
  });
  if (m6 != program.pauses.end() && m6 != program.pauses.begin())
    tool_change = "; its first tool change (M6, tool " + std::to_string(m6->tool) + ") is at line " + line_of(*m6);
  if (m6 != program.pauses.end() && tool_unknown)
    tool_change.append("; the node reports no tool in the spindle (it knows one once an M6 on it is confirmed), so the "
                       "start changes to the line's tool: --tool-in-spindle T says tool T is in");
  throw BadInput(o.file + ": the program pauses (line " + line_of(p) + ": " + gcode::to_string(p.reason) + ")" +
                 tool_change +
                 ", and stdin is not a terminal to confirm it from: run it from a terminal (Enter continues) or "
                 "give --resume-after-s S to continue every pause by itself (nothing was sent)");
}

// Progress on stderr: rewritten in place on a terminal (at most 5 times a
// second), else one line per tenth of the program, per state change and per underrun.
class ProgressPrinter {
 public:
  void operator()(const can_host::StreamProgress& p) {
    const auto now = std::chrono::steady_clock::now();
    const int tenth = static_cast<int>(p.fraction * 10.0);
    const bool news = p.state != last_.state || p.underruns != last_.underruns;
    if (tty_) {
      if (!news && now - printed_ < std::chrono::milliseconds(200)) return;
      std::fprintf(stderr, "\r%s", text(p).c_str());
    } else {
      if (!news && tenth == last_tenth_) return;
      std::fprintf(stderr, "%s\n", text(p).c_str());
    }
    std::fflush(stderr);
    printed_ = now;
    last_ = p;
    last_tenth_ = tenth;
  }
  void end() {
    if (tty_ && last_tenth_ >= 0) std::fputc('\n', stderr);
  }

 private:
  static std::string text(const can_host::StreamProgress& p) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "run: line %-6d %5.1f %%  element %u/%zu  underruns %llu  %-8s", p.line,
                  p.fraction * 100.0, p.running, p.total, static_cast<unsigned long long>(p.underruns),
                  fw::can::to_string(p.state));
    return buf;
  }
  bool tty_ = isatty(STDERR_FILENO) != 0;
  can_host::StreamProgress last_{};
  int last_tenth_ = -1;
  std::chrono::steady_clock::time_point printed_{};
};

void report_score(const hil::PathScore& s, std::uint64_t underruns, Report& report) {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "contour error: max %.4f um   mean %.4f um   std %.4f um\n"
                "path deviation max %.4f um   accel ratio %.3f   jerk ratio %.3f   feed ratio %.3f   cycle %.3f s   "
                "underruns %llu",
                s.contour_error_max_um, s.contour_error_mean_um, s.contour_error_std_um, s.path_deviation_max_um,
                s.accel_ratio_max, s.jerk_ratio_max, s.feed_ratio, s.cycle_time_s,
                static_cast<unsigned long long>(underruns));
  report.line(buf);
  report.data.update(hil::path_score_json(s));
}
// The cut's judgement into the report; a crash fails the run.
void report_cut(const can_host::CutWatch& watch, const can_host::ProgramRunResult& r, Report& report) {
  if (!watch.on()) return;
  const can_host::CutJudgement cut = watch.judge(r.wire);
  report.data["crashes"] = cut.crashes;
  report.data["feed_before_at_speed"] = cut.feed_before_at_speed;
  report.data["feed_onsets"] = cut.feed_onsets;
  char buf[200];
  std::snprintf(buf, sizeof buf, "crashes %llu   feed moves before the spindle was at speed %u (of %u feed starts)",
                static_cast<unsigned long long>(cut.crashes), cut.feed_before_at_speed, cut.feed_onsets);
  report.line(buf);
  if (cut.crashes == 0) return;
  std::string message = "crash: the tool entered the stock with the spindle stopped or slow";
  if (cut.first_crash) message.append(" ").append(*cut.first_crash);
  throw RunFailed(message);
}

int run_program_file(const RunOptions& o, Session& session, Report& report) {
  const gcode::GcodeProgram checked = check_run(o);
  // A run from line without --tool-in-spindle starts with the node's tool: the pauses are checked with it.
  const bool node_says = o.from.from_line != 0 && !o.from.tool_given;
  if (!node_says) check_pauses(o, checked, false);
  can_host::NodeClient& client = session.client();
  can_host::ProgramRunOptions ro;
  ro.rapid_feed_mm_s = o.rapid_feed_mm_s;
  ro.canon = run_setup(o);
  if (node_says) {
    ro.tool_from_node = true;
    ro = can_host::with_node_tool(client, ro);  // asked once; the run uses the same answer
    const int tool = ro.canon.from_line->tool_in_spindle;
    if (tool == 0) {
      check_pauses(o, checked, true);  // none, or not known: as read before
    } else {
      const gcode::GcodeResult again = read_anywhere(o, ro.canon);
      if (again.error) throw BadInput(o.file + ": " + gcode::to_string(*again.error) + " (nothing was sent)");
      check_pauses(o, again.program, false);
    }
  }
  ro.feed_override = o.feed_override;
  ro.telemetry_ms = o.no_score ? 0 : 1;
  ro.window = static_cast<std::size_t>(o.window);
  ro.interrupted = [] { return g_run_interrupted.load(); };
  can_host::OperatorConsole console(STDIN_FILENO, hold_schedule(o),
                                    [&client] { return static_cast<double>(client.bus().now().count()) * 1e-6; });
  ro.feed_hold = [&console] { return console.hold_wanted(); };
  ProgressPrinter printer;
  ro.progress = [&printer](const can_host::StreamProgress& p) { printer(p); };
  ro.on_pause = [&o, &console](const can_host::StreamPause& p) {
    if (o.resume_after_s) {
      std::fprintf(stderr, "\nrun: paused at %s: continuing in %.1f s (--resume-after-s), Ctrl-C stops\n",
                   can_host::pause_text(p).c_str(), *o.resume_after_s);
    } else {
      console.forget_enter();  // an Enter typed before the pause is not an answer to it
      std::fprintf(stderr, "\nrun: paused at %s: press Enter to continue, Ctrl-C stops the program\n",
                   can_host::pause_text(p).c_str());
    }
    std::fflush(stderr);
  };
  ro.resume = [&o, &console](const can_host::StreamPause&, can_host::Micros paused_for) {
    if (console.hold_wanted()) return false;  // the node does not continue a pause while held: resume first
    if (o.resume_after_s) return static_cast<double>(paused_for.count()) * 1e-6 >= *o.resume_after_s;
    return console.take_enter();
  };
  const can_host::CutWatch watch(session.is_emulated() ? session.emulated() : nullptr);
  g_run_interrupted = false;
  auto previous = std::signal(SIGINT, on_run_interrupt);
  can_host::ProgramRunResult r;
  try {
    r = can_host::run_gcode(client, read_file(o.file), ro);
  } catch (const can_host::ProgramInputError& e) {
    std::signal(SIGINT, previous);
    throw BadInput(o.file + ": " + e.what() + " (nothing was run)");  // exit 2
  } catch (...) {
    std::signal(SIGINT, previous);
    printer.end();
    throw;
  }
  std::signal(SIGINT, previous);
  printer.end();

  const can_host::StreamResult& st = r.stream;
  report.line(o.file + ": " + gcode::summary_text(r.program));
  report.data.update(hil::program_summary_json(r.program));
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "%s: %zu elements (%zu on the wire) from (%.4f, %.4f) mm: %zu accepted, streamed at %.0f elements/s "
                "while the queue had room, %.3f s from the first element to the end",
                o.file.c_str(), r.program.segments.size(), r.wire.elements.size(), r.start_mm[0], r.start_mm[1],
                st.acknowledged, st.fill_elements_per_s, st.run_s);
  report.line(buf);
  report.data["program"] = o.file;
  report.data["elements"] = r.wire.elements.size();
  report.data["elements_accepted"] = st.acknowledged;
  report.data["underruns"] = st.underruns;
  report.data["run_s"] = st.run_s;
  report.data["fill_elements_per_s"] = st.fill_elements_per_s;
  report.data["paused_s"] = st.paused_s;
  report.data["held_s"] = st.held_s;
  report.data["feed_hold_changes"] = console.hold_changes();
  nlohmann::json pauses = nlohmann::json::array();
  for (const can_host::StreamPause& p : st.pauses) {
    nlohmann::json j{{"element", p.element}, {"line", p.line}};
    if (p.why) {
      j["reason"] = gcode::to_string(p.why->reason);
      if (p.why->reason == gcode::PauseReason::tool_change) j["tool"] = p.why->tool;
    }
    pauses.push_back(j);
  }
  report.data["pauses"] = pauses;
  if (!st.pauses.empty()) {
    std::snprintf(buf, sizeof buf, "%zu pause%s, %.3f s paused (the run's time includes them)", st.pauses.size(),
                  st.pauses.size() == 1 ? "" : "s", st.paused_s);
    report.line(buf);
  }
  if (console.hold_changes() > 0) {
    std::snprintf(buf, sizeof buf, "feed held %.3f s (%d change%s of the hold switch; the run's time includes it)",
                  st.held_s, console.hold_changes(), console.hold_changes() == 1 ? "" : "s");
    report.line(buf);
  }
  // The node's word (PROGRAM_TOOL), not the program's: unknown after a restart or an unconfirmed change.
  report.data["tool_in_spindle"] = nullptr;
  if (st.final_tool) {
    report.line(o.file + ": in the spindle (the node's PROGRAM_TOOL): " + can_host::to_string(*st.final_tool));
    if (st.final_tool->known) report.data["tool_in_spindle"] = st.final_tool->tool;
  }
  if (st.end == can_host::StreamResult::End::interrupted) {
    if (st.acknowledged == 0) throw RunFailed("stopped by Ctrl-C before the program started: nothing moved");
    const std::uint32_t element = std::max<std::uint32_t>(st.final_status.element, 1);
    const int line = element <= r.wire.elements.size() ? r.wire.elements[element - 1].line : 0;
    throw RunFailed("stopped by Ctrl-C at line " + std::to_string(line) +
                    ": the table came to a controlled stop on the path and holds there; the rest of the program "
                    "was dropped");
  }
  report_cut(watch, r, report);
  if (st.end == can_host::StreamResult::End::failed) throw RunFailed(st.message);
  if (st.final_heartbeat) require_no_fault(*st.final_heartbeat, client, "the program");
  if (r.score) {
    report_score(*r.score, st.underruns, report);
    report.data["samples"] = r.samples.size();
    report.data["telemetry_complete"] = r.telemetry_complete;
    if (!r.telemetry_complete)
      std::fprintf(stderr, "tnvctl: run: warning: the node dropped telemetry frames: the score misses ticks\n");
  } else {
    std::snprintf(buf, sizeof buf, "done after %.3f s, underruns %llu (not scored: --no-score)", st.run_s,
                  static_cast<unsigned long long>(st.underruns));
    report.line(buf);
  }
  return kExitOk;
}

constexpr const char* kRunHelp =
    "Stream an RS274/NGC program to the node and score the run.\n\n"
    "WHAT IT DOES\n"
    "  1. Parses FILE (nothing is sent if it does not parse: the error names the line, and the column\n"
    "     where the interpreter found it).\n"
    "  2. Reads the node's planner limits (x/y.path.*, path.tolerance_mm, soft travel limits) and where the table\n"
    "     stands, and parses FILE again from there with those limits.\n"
    "  3. Takes command ownership, sets tlm.position_ms to 1 (restored at the end), enables\n"
    "     the servo if it is off, and streams the program as SEGMENT / SEGMENT_TAIL frames with flow control\n"
    "     (never more elements on their way than the node's motion queue has free slots).\n"
    "  4. Ends the program, waits for the node to run it to its end, and prints the score.\n\n"
    "G-CODE\n"
    "  LinuxCNC's RS274/NGC dialect, as `tnvctl gcode canon` reads it (docs/gcode.md): work offsets, tools,\n"
    "  parameters, O-word subroutines and flow, cutter compensation. --tool-table, --var-file and\n"
    "  --subroutine-path as for `tnvctl gcode canon`. Moves are in X, Y and Z (G43's tool length counts in Z;\n"
    "  a G17 arc with a Z end is a helix); rigid tapping and a G5.1 spline are refused with their line. A probe\n"
    "  move (G38.2-G38.5) runs: what precedes it is sent, the node's PROBE_RESULT awaited, #5061-#5070 set\n"
    "  from it and the rest read from where the table rests (a G38.2/G38.4 that does not trip stops the\n"
    "  program at its line; docs/gcode.md \"Probe moves\"); before the run, such a program is parsed as if no\n"
    "  probe tripped. M0, M1 (with --optional-stop on, the default) and M6 (a manual tool change)\n"
    "  pause the program: see PAUSES. S, M3, M4 and M5 start and stop the spindle where the program reaches\n"
    "  them (at rest; feed moves wait for it at speed); coolant (M7/M8) is counted and not sent. The program\n"
    "  ends at M2, M30, the closing % or the end of the file.\n"
    "  Before the run: lines run, segments, tool changes and the programmed cycle time.\n\n"
    "PROGRESS\n"
    "  On stderr: the G-code line being run, the share of the program's length done, the element and the\n"
    "  underruns (the queue ran dry: the table waits at rest on the path and goes on when elements arrive).\n\n"
    "RUN FROM LINE\n"
    "  --from-line N starts at line N (the Nth line run: --from-pass K for a line in a loop) with the modal state\n"
    "  the full run has there; from where the table stands the tool goes up to --clearance-z, across at rapid and\n"
    "  down to the start, the last --approach-height mm at the feed (docs/gcode.md \"Run from line\"). A tool other\n"
    "  than --tool-in-spindle (default: the node's, when it knows it; else none) is changed first: a pause. The\n"
    "  spindle is started as the line has it. A probe (G38.x) before N is skipped: a start where the position or\n"
    "  an offset depends on where it tripped, or a line that reads its result (#5061-#5070), is refused.\n\n"
    "PAUSES\n"
    "  The table comes to rest at the pause and holds there; the spindle is left as it is. tnvctl prints the\n"
    "  line, the reason and, for M6, the tool, and waits for Enter on the terminal (COMMAND cycle_start). With\n"
    "  --resume-after-s S it continues by itself after S seconds. A program that pauses is refused before\n"
    "  anything is sent when stdin is not a terminal and --resume-after-s is not given. Waiting keeps the\n"
    "  node's host timeout fed; Ctrl-C while paused stops the program there.\n\n"
    "FEED HOLD\n"
    "  On a terminal the space key holds the feed (COMMAND feed_hold: the table brakes on the path at the planner's\n"
    "  deceleration and waits there, the spindle keeps turning, a dwell's clock stops) and the next space resumes it\n"
    "  (feed_resume). Without a terminal: SIGUSR1 holds, SIGUSR2 resumes (kill -USR1 PID). --hold-at S and\n"
    "  --resume-at S (each repeatable, in pairs) hold on a schedule, seconds from the program's start. The\n"
    "  report gives the time held (--json held_s). A hold is not a pause: Enter does not end it, and an Enter\n"
    "  while held is dropped (a pause reached while held continues after the resume and an Enter).\n\n"
    "CTRL-C\n"
    "  A controlled stop on the path (COMMAND abort_program): the table brakes along the programmed path, holds\n"
    "  there, the rest of the program is dropped; tnvctl exits 1 naming the line it stopped at.\n\n"
    "SCORE (also --json, the keys of `tnv-hil path` plus underruns)\n"
    "  contour_error_max_um / _mean_um / _std_um: measured position to the nearest point of the programmed lines\n"
    "  and arcs; path_deviation_max_um: the same for the reference; accel_ratio_max, jerk_ratio_max: largest\n"
    "  finite difference of the 1 ms reference over the axis limit; feed_ratio: programmed time (length / F) over\n"
    "  the cycle time; cycle_time_s; underruns. Sampled from TLM_POSITION_X and _Y every 1 ms (22 % of a\n"
    "  1 Mbit/s bus, below every control frame in priority); --no-score leaves telemetry alone. --json also has\n"
    "  program, elements, elements_accepted, samples, telemetry_complete, run_s and fill_elements_per_s.\n\n"
    "GLOBAL OPTIONS\n"
    "  --iface IFACE or --emu, --node, --host-id, --timeout-ms (per answer), --json: see `tnvctl --help`.\n\n"
    "CUTTING (--emu)\n"
    "  Judged from the emulated machine, not the node's word: crashes (the tool entered the stock, an\n"
    "  --emu-scenario with [stock] enabled, with the spindle stopped or below half its command) and\n"
    "  feed_before_at_speed (a feed move started from rest while the spindle drive was commanded on and not at\n"
    "  speed), with feed_onsets, in the text and --json. A crash fails the run (exit 1).\n\n"
    "EXIT CODES\n"
    "  0 the program ran to its end; 1 refused, stopped (Ctrl-C, fault, host timeout), timed out or crashed\n"
    "  (--emu); 2 bad command line or program (nothing was run).\n\n"
    "EXAMPLES\n"
    "  tnvctl --emu run tests/data/paths/circle_chords_0p1mm.ngc\n"
    "  tnvctl --iface can0 run part.ngc --feed-override 0.5 --json";

}  // namespace

void add_run_commands(CLI::App& app, ActionSlot& slot) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "stream a G-code program (FILE.ngc) to the node, show progress, score it");
  cmd->footer(kRunHelp);
  cmd->add_option("file", o->file, "RS274/NGC program")->required();
  cli::add_gcode_setup_options(*cmd, o->files);
  cli::add_from_line_options(*cmd, o->from);
  cli::add_feed_hold_options(*cmd, o->holds);
  cmd->add_option("--feed-override", o->feed_override, "path speed ratio 0..1.5, applied once the program runs");
  cmd->add_option("--rapid-feed", o->rapid_feed_mm_s, "G0 path speed, mm/s")->capture_default_str();
  cmd->add_flag("--no-score", o->no_score, "leave telemetry as it is and print no score");
  cmd->add_option("--resume-after-s", o->resume_after_s,
                  "continue each program pause (M0, M1, M6) by itself after this many seconds; without it the "
                  "operator presses Enter");
  cmd->add_option("--window", o->window, "elements sent ahead of their answers")
      ->check(CLI::Range(1, 15))
      ->capture_default_str();
  cmd->callback([&slot, o] {
    slot = Action{"run", true, [o](Session& s, Report& r) { return run_program_file(*o, s, r); },
                  [o] { check_run(*o); }};
  });
}

}  // namespace tnv::tnvctl
