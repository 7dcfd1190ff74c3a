#pragma once
// tnv-hil path: a G-code program run by the firmware on the emulated table.
// The program is read for the table's home (tools/gcode), streamed into the
// tick task's motion queue as room frees up (as a host streams over CAN),
// and every tick's reference and measured position are scored against the
// exact programmed geometry (tools/score/path_score.hpp). A pause continues
// after PathRunOptions::resume_after_s; the ticks it rests are left out of
// the score (its cycle time is the program's motion, not the operator's wait).
// Feed holds (PathRunOptions::feed_holds) are TickTask::feed_hold, what the
// node's COMMAND feed_hold does: their ticks are scored (the braking, the
// rest on the path and the restart are the machine's motion).
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "emulator/scenario.hpp"
#include "emulator/spindle_crash_log.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/tick/tick_record.hpp"
#include "tools/gcode/feed_hold_schedule.hpp"
#include "tools/gcode/gcode_program.hpp"
#include "tools/score/path_score.hpp"

namespace tnv::hil {

struct PathRunOptions {
  double rapid_feed_mm_s = 50.0;  // G0 path speed
  gcode::CanonSetup canon{};      // tool table, parameters, subroutine path (gcode_program.hpp)
  bool keep_samples = false;      // every tick's reference and position (plots, CSV)
  // A program pause (M0, M1, M6) continues (TickTask::cycle_start) after
  // resting this long, as an operator would; its ticks are not scored.
  double resume_after_s = 1.0;
  // The feed held from each window's hold to its resume, seconds from the first tick of the program.
  std::vector<gcode::FeedHoldWindow> feed_holds;
};

struct PathHold {
  gcode::FeedHoldWindow window;
  bool applied = false;                  // false: the program had ended before the hold's time
  double path_speed_at_hold_mm_s = 0.0;  // the planner's path speed when the hold was asked
  double stopped_after_s = -1.0;         // from the hold to the path speed's first 0 (-1: not before the resume)
  double spindle_rpm_min_held = 0.0;     // the smallest |measured spindle speed| once the path rested, held
  double spindle_rpm_max_held = 0.0;     // the largest, likewise
};

struct PathPause {
  gcode::ProgramPause why;  // as the program has it (segment index, reason, tool)
  int line = 0;
  double paused_s = 0.0;    // from the tick it reported paused to cycle start
};

struct PathRunResult {
  bool completed = false;
  std::string error;                    // why not: a G-code error (line, column), a refusal, a fault
  bool faulted = false;                 // not completed: the firmware faulted
  bool timed_out = false;               // not completed: the program did not finish in its generous time
  // Judged from the machine (feed_start_judge.hpp): a crash fails the run
  // (error set, completed stays as the program ran).
  std::uint64_t crashes = 0;            // the stock engaged with the spindle stopped or slow ([stock] on)
  std::vector<emu::CrashEvent> crash_events;  // the first few
  std::uint32_t feed_onsets = 0;        // feed moves started from rest
  std::uint32_t feed_before_at_speed = 0;  // ... of them with the spindle commanded on and not at speed
  double tool_force_max_n = 0.0;        // the milling force where the tool is, largest at a tick ([stock] on)
  std::array<double, hal::kAxisCount> cutting_load_max_mm_s{};  // largest |d_cut| each axis took (judge side)
  PathScore score{};
  std::uint64_t underruns = 0;          // the queue ran dry before the program's end
  std::uint64_t segments = 0;           // segments streamed
  std::uint64_t guard_failures = 0;     // planner second-difference guard found no speed (never expected)
  double programmed_length_mm = 0.0;
  fw::TickCounters counters{};
  gcode::GcodeProgram program;             // as read for where the table stood
  std::vector<PathSample> samples;  // from the first streamed segment, when keep_samples
  std::vector<double> path_speed_mm_s;     // the planner's path speed, with samples
  std::vector<PathPause> pauses;           // in the order reached
  std::vector<PathHold> holds;             // one per PathRunOptions::feed_holds window
  double held_s = 0.0;                     // ticks held, in seconds
};

// One run of `gcode_text` with `controller` on both axes.
PathRunResult run_path(const emu::Scenario& scenario, const fw::FirmwareConfig& config, fw::ControllerKind controller,
                       const std::string& gcode_text, const PathRunOptions& options = {});

struct PathSweepResult {
  std::vector<PathRunResult> per_seed;  // seed 0 keeps its samples when asked
  PathScore mean{};              // contour statistics, feed ratio and cycle time averaged over seeds;
                                        // path deviation, accel and jerk ratios the largest of any seed
  std::uint64_t underruns = 0;          // summed over seeds
  std::uint64_t crashes = 0;            // summed over seeds
  std::uint32_t feed_before_at_speed = 0;  // summed over seeds
  std::string error;                    // the first seed's error, "" when all completed
};

// `seeds` runs (seeded scenarios, hil/seeded_scenario.hpp) on the machine's cores.
PathSweepResult run_path_seeds(const emu::Scenario& scenario, const fw::FirmwareConfig& config,
                               fw::ControllerKind controller, const std::string& gcode_text, int seeds,
                               const PathRunOptions& seed0_options,
                               const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace tnv::hil
