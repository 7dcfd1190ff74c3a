#include "tools/hil/path_run.hpp"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cmath>
#include <limits>
#include <optional>
#include <thread>

#include "emulator/cutting_at_tool.hpp"
#include "tools/gcode/probe_outcome.hpp"
#include "tools/hil/command_status_text.hpp"
#include "tools/hil/feed_start_judge.hpp"
#include "tools/hil/hil_rig.hpp"
#include "tools/hil/program_feeder.hpp"
#include "tools/hil/seeded_scenario.hpp"

namespace tnv::hil {

namespace {

// The crash log of a machine with a stock, into the run's result; a crash fails the run.
void take_crashes(const emu::Machine& machine, PathRunResult& result) {
  const emu::CuttingAtTool* cut = machine.cutting_at_tool();
  if (cut == nullptr) return;
  const emu::SpindleCrashLog& log = cut->crashes();
  result.crashes = log.count();
  for (std::size_t i = 0; i < std::min<std::size_t>(log.count(), emu::SpindleCrashLog::kKept); ++i)
    result.crash_events.push_back(log.event(i));
  if (result.crashes == 0) return;
  const emu::CrashEvent& e = log.event(0);
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "crash: the tool entered the stock at %.3f s, (%.3f, %.3f, %.3f) mm, spindle %.0f rpm of %.0f "
                "commanded (%llu crash%s)",
                e.time_s, e.x_mm, e.y_mm, e.z_mm, e.spindle_rpm, e.commanded_rpm,
                static_cast<unsigned long long>(result.crashes), result.crashes == 1 ? "" : "es");
  // The crash first: a fault that follows it (a stalled axis) is its consequence.
  result.error = result.error.empty() ? std::string(buf) : std::string(buf).append("; then ").append(result.error);
}

PathSample sample_of(const fw::TickRecord& r) {
  PathSample s;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    s.position_mm[i] = r.axis[i].position_mm;
    s.reference_mm[i] = r.axis[i].reference_mm;
  }
  return s;
}

}  // namespace

PathRunResult run_path(const emu::Scenario& scenario, const fw::FirmwareConfig& config, fw::ControllerKind controller,
                       const std::string& gcode_text, const PathRunOptions& options) {
  PathRunResult result;
  std::unique_ptr<HilRig> rig = HilRig::create(scenario, config, controller, result.error);
  if (!rig) return result;
  fw::TickTask& task = rig->task;
  rig->home();
  if (const fw::CommandStatus st = task.hold_position(); st != fw::CommandStatus::ok) {
    result.error = "servo-on refused: " + command_status_text(st, task);
    return result;
  }
  rig->tick();
  // The program starts where the table holds, with the planner's own limits.
  gcode::GcodeOptions parse;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) parse.start_mm[i] = task.standing_mm(hal::axis_from_index(i));
  parse.rapid_feed_mm_s = options.rapid_feed_mm_s;
  parse.limits = task.motion().limits();
  parse.canon = options.canon;

  std::vector<PathSample> samples;
  samples.push_back(sample_of(task.last_record()));
  std::optional<ProgramFeeder> feeder;
  FeedStartJudge judge;
  const std::uint64_t done_before = task.motion().stats().segments_done;
  const emu::CuttingAtTool* tool_cut = rig->machine.cutting_at_tool();
  // Generous: the programmed time three times over, plus ten seconds, plus the pauses.
  const auto resume_ticks = static_cast<std::int64_t>(std::llround(std::max(0.0, options.resume_after_s) / kTickPeriodS));
  double holds_s = 0.0;
  for (const gcode::FeedHoldWindow& w : options.feed_holds) {
    holds_s += w.resume_at_s - w.hold_at_s;
    PathHold h;
    h.window = w;
    result.holds.push_back(h);
  }
  const auto hold_ticks = static_cast<std::int64_t>(std::ceil(holds_s / kTickPeriodS));
  const auto max_ticks = [&](const gcode::GcodeProgram& program) {
    return static_cast<std::int64_t>(program.programmed_time_s() * 3000.0) + 10'000 +
           static_cast<std::int64_t>(program.pauses.size()) * resume_ticks + hold_ticks;
  };
  std::int64_t ticks = 0;
  std::int64_t paused_ticks = -1;  // >= 0 while the task rests at a pause
  bool held = false;
  std::size_t hold_index = 0;      // the window of the hold on now (or the last one)
  enum class Step { go, stop, error };  // stop: faulted or ended; error: result.error says why
  // One tick of `program` as read so far.
  const auto step = [&](const gcode::GcodeProgram& program) {
    // The operator's hold switch, as COMMAND feed_hold / feed_resume set it on the node.
    const double t_s = static_cast<double>(ticks) * kTickPeriodS;
    if (const bool want = gcode::feed_held_at(options.feed_holds, t_s); want != held) {
      if (const fw::CommandStatus st = task.feed_hold(want); st != fw::CommandStatus::ok) {
        result.error = std::string(want ? "feed hold" : "feed resume") + " at " + std::to_string(t_s) +
                       " s refused: " + command_status_text(st, task);
        return Step::error;
      }
      held = want;
      if (held) {
        while (hold_index + 1 < result.holds.size() && result.holds[hold_index].window.resume_at_s <= t_s) ++hold_index;
        PathHold& h = result.holds[hold_index];
        h.applied = true;
        h.path_speed_at_hold_mm_s = task.motion().path_speed_mm_s();
        h.spindle_rpm_min_held = std::numeric_limits<double>::infinity();
      }
    }
    // Stream as a host would: as many segments as there are free slots.
    if (!feeder->feed(task)) {
      const fw::motion::SegmentRefusal why = feeder->last_refusal();
      result.error = "segment of line " + std::to_string(program.segments[feeder->next_index()].tag) + " refused: " +
                     command_status_text(feeder->last_status(), task) +
                     (why != fw::motion::SegmentRefusal::none ? std::string(" (") + fw::motion::to_string(why) + ")"
                                                               : std::string());
      return Step::error;
    }
    result.segments = feeder->next_index();
    rig->tick();
    judge.observe(rig->machine, static_cast<std::size_t>(task.motion().stats().segments_done - done_before));
    if (tool_cut != nullptr) result.tool_force_max_n = std::max(result.tool_force_max_n, tool_cut->force().force_n());
    for (std::size_t i = 0; i < hal::kAxisCount; ++i)
      result.cutting_load_max_mm_s[i] =
          std::max(result.cutting_load_max_mm_s[i], std::fabs(rig->machine.truth(hal::axis_from_index(i)).cutting_mm_s));
    if (task.motion().state() == fw::motion::MotionState::paused) {
      if (paused_ticks < 0) {
        paused_ticks = 0;
        PathPause p;
        // Pauses are reached in program order.
        if (result.pauses.size() < program.pauses.size()) {
          p.why = program.pauses[result.pauses.size()];
          p.line = static_cast<int>(program.segments[p.why.segment].tag);
        }
        result.pauses.push_back(p);
      }
      if (++paused_ticks >= resume_ticks) {
        result.pauses.back().paused_s = static_cast<double>(paused_ticks) * kTickPeriodS;
        if (const fw::CommandStatus st = task.cycle_start(); st != fw::CommandStatus::ok) {
          result.error = "cycle start refused: " + command_status_text(st, task);
          return Step::error;
        }
        paused_ticks = -1;
      }
      return Step::go;  // the operator's wait is not scored
    }
    if (held) {
      result.held_s += kTickPeriodS;
      PathHold& h = result.holds[hold_index];
      if (h.stopped_after_s < 0.0 && task.motion().path_speed_mm_s() == 0.0)
        h.stopped_after_s = t_s + kTickPeriodS - h.window.hold_at_s;
      if (h.stopped_after_s >= 0.0) {
        const double rpm = std::fabs(task.last_record().spindle.measured_rpm);
        h.spindle_rpm_min_held = std::min(h.spindle_rpm_min_held, rpm);
        h.spindle_rpm_max_held = std::max(h.spindle_rpm_max_held, rpm);
      }
    }
    samples.push_back(sample_of(task.last_record()));
    if (options.keep_samples) result.path_speed_mm_s.push_back(task.motion().path_speed_mm_s());
    if (task.state() == fw::MotionState::faulted) return Step::stop;
    if (feeder->closed() && task.state() == fw::MotionState::holding) return Step::stop;
    return Step::go;
  };
  // A probe move (the last segment read): run what is read until its outcome.
  parse.run_probe = [&](const gcode::GcodeProgram& so_far) {
    gcode::ProbeRun run;
    if (!feeder) feeder.emplace(so_far.segments);
    feeder->follow(so_far.segments, true);
    const std::uint32_t count_before = task.probe_report().count;
    while (task.probe_report().count == count_before) {
      const Step s = ticks < max_ticks(so_far) ? step(so_far) : Step::stop;
      ++ticks;
      if (s == Step::error) run.error = result.error;
      else if (s == Step::stop)
        run.error = task.state() == fw::MotionState::faulted
                        ? "fault: " + command_status_text(fw::CommandStatus::faulted, task)
                        : std::string("the probe move did not end in three times its programmed time");
      if (!run.error.empty()) return run;
    }
    const fw::ProbeReport& p = task.probe_report();
    return gcode::probe_run(p.outcome, so_far.segments.back().probe, p.trip_mm, p.rest_mm);
  };
  const gcode::GcodeResult parsed = gcode::parse_gcode(gcode_text, parse);
  if (parsed.error) {
    result.error = gcode::to_string(*parsed.error);
    return result;
  }
  const gcode::GcodeProgram& program = parsed.program;
  result.programmed_length_mm = program.programmed_length_mm();
  samples.reserve(static_cast<std::size_t>(program.programmed_time_s() * 1100.0) + 1000);
  if (!feeder) feeder.emplace(program.segments);
  feeder->follow(program.segments, false);
  for (; ticks < max_ticks(program); ++ticks) {
    const Step s = step(program);
    if (s == Step::error) return result;
    if (s == Step::stop) break;
  }
  for (PathHold& h : result.holds)
    if (!std::isfinite(h.spindle_rpm_min_held)) h.spindle_rpm_min_held = 0.0;
  result.counters = task.counters();
  const FeedStartCount feed_starts = judge.count(program.segments);
  result.feed_onsets = feed_starts.feed_onsets;
  result.feed_before_at_speed = feed_starts.feed_before_at_speed;
  const fw::motion::MotionStats stats = task.motion().stats();
  result.underruns = stats.underruns;
  result.guard_failures = stats.follower.guard_failures;
  PathScoreOptions score_options;
  score_options.tick_period_s = kTickPeriodS;
  result.score = score_path(program, samples, task.motion().limits(), score_options);
  if (task.state() == fw::MotionState::faulted) {
    result.faulted = true;
    result.error = "fault: " + command_status_text(fw::CommandStatus::faulted, task);
  } else if (!feeder->closed() || task.state() != fw::MotionState::holding) {
    result.timed_out = true;
    result.error = "the program did not finish in three times its programmed time";
  } else {
    result.completed = true;
  }
  take_crashes(rig->machine, result);
  if (options.keep_samples) result.samples = std::move(samples);
  result.program = parsed.program;
  return result;
}

PathSweepResult run_path_seeds(const emu::Scenario& scenario, const fw::FirmwareConfig& config,
                               fw::ControllerKind controller, const std::string& gcode_text, int seeds,
                               const PathRunOptions& seed0_options,
                               const std::function<void(std::size_t, std::size_t)>& progress) {
  PathSweepResult out;
  const auto n = static_cast<std::size_t>(std::max(1, seeds));
  out.per_seed.resize(n);
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> done{0};
  auto worker = [&] {
    for (std::size_t s = next++; s < n; s = next++) {
      PathRunOptions options = seed0_options;
      options.keep_samples = s == 0 && seed0_options.keep_samples;
      out.per_seed[s] = run_path(seeded(scenario, static_cast<int>(s)), config, controller, gcode_text, options);
      const std::size_t finished = ++done;
      if (progress) progress(finished, n);
    }
  };
  const unsigned threads = static_cast<unsigned>(std::min<std::size_t>(std::max(1u, std::thread::hardware_concurrency()), n));
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < threads; ++i) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();

  for (std::size_t s = 0; s < n; ++s) {
    const PathRunResult& r = out.per_seed[s];
    if (!r.error.empty() && out.error.empty()) out.error = "seed " + std::to_string(s) + ": " + r.error;
    const PathScore& p = r.score;
    PathScore& m = out.mean;
    const double w = 1.0 / static_cast<double>(n);
    m.contour_error_max_um += w * p.contour_error_max_um;
    m.contour_error_mean_um += w * p.contour_error_mean_um;
    m.contour_error_std_um += w * p.contour_error_std_um;
    m.feed_ratio += w * p.feed_ratio;
    m.cycle_time_s += w * p.cycle_time_s;
    m.path_deviation_max_um = std::max(m.path_deviation_max_um, p.path_deviation_max_um);
    m.accel_ratio_max = std::max(m.accel_ratio_max, p.accel_ratio_max);
    m.jerk_ratio_max = std::max(m.jerk_ratio_max, p.jerk_ratio_max);
    m.window_samples += p.window_samples;
    out.underruns += r.underruns;
    out.crashes += r.crashes;
    out.feed_before_at_speed += r.feed_before_at_speed;
  }
  return out;
}

}  // namespace tnv::hil
