#pragma once
// Issue 8 item 5 on the board: the robust ARSC at the tick on the emulated
// TNV-40. The force loop is the firmware's own feed-override source
// (fw::arsc::ArscFeedSource inside fw::TickTask::tick, switched on and
// tuned by FirmwareConfig::arsc, the arsc.* parameters): the table cuts a
// program pushed as planner segments (TickTask::push_segment), the source
// reads the force the tick latched and sets the feed override, and the
// look-ahead planner and the R-DVSC+DDC axis loops make the table follow.
// This file only sets the machine up, pushes the program and judges.
// emu::Machine with [milling] on (the S3 force on X), the real FPGA driver,
// the emulated bus (HilRig).
//
// Before the cut a test-and-learning stage on a separate machine at the
// start depth runs the same kind of program with the loop off and a
// two-level feed override, and fits the loop's continuous-time model (force
// time constant, cutting gain, the lag from a feed command to the table's
// feed): it never reads the scenario's parameters. The fit becomes the
// arsc.* model parameters.
#include <array>
#include <complex>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "emulator/scenario.hpp"
#include "firmware/adaptive/arsc/outer_gain_solve.hpp"
#include "firmware/adaptive/arsc/pole_sets.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/tick/tick_record.hpp"
#include "tools/hil/arsc_tick_path.hpp"

namespace tnv::hil {

// --path stock-step (issue 27, "S3 on a real cut"): the force is the
// emulator's milling force where the tool is ([stock] on, [milling] off;
// reference plant "Stock, and cutting where the tool is"), the spindle turns
// at spindle_rpm from before the program, and the program steps down in Z
// once inside the stock, so a_p goes start_depth_mm -> start_depth_mm +
// step_mm. The stock is placed from the table's power-up position: its top
// start_depth_mm above the tool point, its side entry_mm ahead of the
// tool's edge in +X (the tool enters it from the side, cutting).
struct StockStepCase {
  double spindle_rpm = 6000.0;
  double start_depth_mm = 1.0;
  double step_mm = 1.0;             // 1 -> 2 mm: the 2:1 step of issue 27's goal
  double entry_mm = 2.0;
  double step_after_mm = 80.0;      // X travel from the start to the step (about 4 s in at 150 N)
  // X travel over which Z steps down: 1 mm with a 1 mm step is a 45 deg ramp, whose corners the planner
  // takes at about 4 mm/s (5 um path tolerance); a longer one is a gentler corner and a slower step.
  double step_ramp_mm = 1.0;
  double length_mm = 240.0;         // X travel of the program (the constant-feed baseline does not run out)
  double test_stage_feed_mm_s = 20.0;  // about 150 N at the start depth (the [milling] case's 40 is 250 N here)
  double judged_after_s = 1.0;      // the goal: within 10 % of f* this long after the step
};

struct TickStudyConfig {
  std::string label = "1 ms";
  std::uint32_t ticks_per_sample = 1;   // arsc.period_ticks (150 = the paper's 0.15 s)
  fw::arsc::PoleSet poles = fw::arsc::PoleSet::case1;
  double pole_speedup = 1.0;            // force-loop poles this many times faster than the paper's (continuous time)
  bool outer_loop = true;               // false: arsc.enable off, the program at a constant feed (the baseline)
  double constant_feed_mm_s = 20.0;     // the baseline's feed: about the loop's mean feed (same X travel)
  StudyPath path = StudyPath::line;
  double program_feed_mm_s = 60.0;      // F of every segment: the override's 1.5 lets the loop ask for 90 mm/s
  double segment_mm = 10.0;             // straight lines go to the queue in pieces of this length
  double soft_start_s = 1.0;            // arsc.soft_start_s
  double force_ref_n = 150.0;           // S3 experiment
  double memory_s = 0.15;               // arsc.memory_s
  bool adapt = true;                    // false: arsc.adapt off (the test stage's gain, fixed gains)
  // Depth 0.2 -> 1.0 -> 0.2 mm over 5 + 5 s, then 0.5 s at 0.2 mm (the paper's 15 + 15 s needs 600 mm of X).
  double duration_s = 10.5;
  double settle_s = 3.0;
  double test_stage_s = 4.0;
  // Two-level feed command of the test stage: mean +- step. A small step: the planner turns a feed
  // step into a ramp at its path acceleration, which a first-order fit would read as lag (+-10 mm/s:
  // 26 ms, and the 1 ms loop with 4x poles then holds 0.42 % instead of 0.22 %).
  double test_stage_feed_mm_s = 40.0;
  double test_stage_step_mm_s = 2.0;
  // Where the program starts (zero() on both axes at power-up: the table stands near one end of its
  // travel), where it ends along X, and where the arc path turns.
  fw::motion::PlanePoint start_mm{-240.0, -240.0};
  double end_x_mm = 245.0;
  double arc_at_x_mm = -165.0;          // reached 4.0 to 5.1 s into the cut at 150 N: inside the scored part
  // The planner's per-axis limits. Acceleration 2000 mm/s^2 as the jog of the earlier study (the
  // drive could accelerate at about 31,000 mm/s^2; on the emulated node the firmware's default
  // 500 mm/s^2 gave the same 0.22 % peak, docs/reproduction-s3.md), jerk
  // 200,000 mm/s^3 so that the jerk filter keeps its default 20 ticks (taps = 2 a / (j dt)).
  fw::PathLimits path_limits{.speed_mm_s = 100.0, .accel_mm_s2 = 2000.0, .jerk_mm_s3 = 200000.0};
  emu::MillingParams milling{.enabled = true, .depth = {0.2, 1.0, 5.0, 5.0}};
  // The table the study and its test stage run on (tnv-hil arsc tick --scenario): its plant, [noise],
  // [io] and the rest apply as in any run; its [milling] is replaced by `milling` above. The default
  // is the reference table.
  emu::Scenario table{};
  StockStepCase stock{};  // path stock_step only
};

// The test-and-learning stage's fit (continuous time, physical units).
struct TickTestStage {
  double force_time_constant_s = 0.0;
  double cutting_gain_n_per_mm_s = 0.0;  // G = K delta at the start depth, per mm/s of path feed
  double drive_time_constant_s = 0.0;
  double drive_gain = 0.0;               // table feed per commanded feed, steady state
  double force_rms_n = 0.0;              // residuals of the two fits
  double drive_rms_mm_s = 0.0;
  std::size_t samples = 0;
};

struct TickStudyPoint {
  double t_s = 0.0;
  double depth_mm = 0.0;
  double force_n = 0.0;          // measured (ADC)
  double force_ref_n = 0.0;      // the loop's f* (soft start included)
  double feed_mm_s = 0.0;        // table speed along the path (judge side)
  double command_mm_s = 0.0;     // feed override x the programmed feed
  double feed_override = 0.0;
  double cutting_gain_n_per_mm_s = 0.0;       // the loop's estimate
  double true_cutting_gain_n_per_mm_s = 0.0;  // K delta v_x / |v| (judge side, for the plot)
  double x_mm = 0.0;
  double y_mm = 0.0;
};

struct TickStudyResult {
  TickStudyConfig config{};
  std::vector<TickStudyPoint> trace;  // every 10 ms
  TickTestStage test_stage{};
  double period_s = 0.0;
  double force_error_max_pct = 0.0;   // after settle_s, of force_ref_n, every tick
  double force_error_max_at_s = -1.0;
  double force_error_rms_pct = 0.0;
  // The same against the milling force itself (the emulator's, without the ADC's noise and steps).
  double force_error_true_max_pct = 0.0;
  double force_error_true_rms_pct = 0.0;
  // A firmware fault, or (force loop on) the force pinned at the ADC's full scale (2 f*) for 0.1 s;
  // the run stops there and the error counts as at least 100 %.
  bool diverged = false;
  double diverged_at_s = -1.0;
  std::string fault;                  // the firmware fault, if any
  std::uint64_t ticks = 0;                  // ticks run (the whole duration unless diverged)
  std::uint64_t adc_full_scale_ticks = 0;   // force reading at the ADC's full scale (force unknown above)
  std::uint64_t dac_saturated_ticks = 0;    // X DAC code at either rail
  double dac_saturated_longest_s = 0.0;     // longest unbroken run at a rail
  double first_dac_saturation_s = -1.0;     // -1: never
  std::uint32_t clamped_samples = 0;        // the loop's command at the edge of its override range
  std::uint32_t clamped_after_settle = 0;   // ... of them from settle_s on (the rest: the soft start)
  double last_clamp_s = -1.0;               // time of the last clamped sample, -1: none
  std::uint32_t samples = 0;                // the loop's samples (the source's count)
  std::uint32_t refused_updates = 0;        // gain designs refused (last good gains kept)
  std::uint32_t refused_segments = 0;       // segments the firmware refused
  double program_end_s = -1.0;              // the program ran out (the table left the cut) before the end
  // The commanded reference x_ref,k of both axes, by finite differences
  // (docs/motion.md "How the limits are measured"), over the planner's limits.
  double accel_ratio_max = 0.0;
  double jerk_ratio_max = 0.0;
  double override_min_seen = 0.0;           // feed override while the program ran
  double override_max_seen = 0.0;
  double travel_mm = 0.0;                   // along the path (encoders)
  double travel_x_mm = 0.0;
  double max_feed_mm_s = 0.0;               // along the path (judge side)
  fw::arsc::OuterPoles poles{};             // force-loop poles, rad/s
  std::array<std::complex<double>, 4> target_z{};  // all four closed-loop poles asked for, z at the period
  fw::arsc::OuterGains initial_gains{};     // at the test-stage model, normalised
  double max_abs_gain = 0.0;                // over the run, normalised
  fw::arsc::ArscSourceParams arsc{};        // what the board was told (arsc.*)
  // path stock_step: the step (the first tick a_p is 0.01 mm past the start depth, judge side)
  // and the force error judged_after_s later: at that tick and the worst
  // from then to the end; against the milling force itself and as the ADC
  // read it. -1 / 0 when the step was not reached.
  double step_at_s = -1.0;
  double step_error_pct = 0.0;
  double step_error_measured_pct = 0.0;
  double after_step_max_pct = 0.0;
  double after_step_measured_max_pct = 0.0;
  double depth_before_mm = 0.0;             // a_p just before and 1 s after the step
  double depth_after_mm = 0.0;
  double feed_before_mm_s = 0.0;            // path feed 0.5 s before the step and 1 s after it (judge side)
  double feed_after_mm_s = 0.0;
  std::uint64_t crashes = 0;                // the stock engaged with a slow spindle (never expected)
  std::string error;                        // set if the run could not start
};

// `table` with the study's milling force (and, for the test stage's separate cut, its own noise realisation).
emu::Scenario tick_study_scenario(const emu::Scenario& table, const emu::MillingParams& milling);
// path stock_step: `table` with its stock placed for the case and [milling] off.
emu::Scenario stock_step_scenario(const emu::Scenario& table, const StockStepCase& k);
// The scenario of a study (its test stage: with `milling` at the start depth).
emu::Scenario study_scenario(const TickStudyConfig& config, const emu::MillingParams& milling);
// The program the study cuts at `feed_mm_s` (the test stage: always without the step).
StudyProgram study_cut_program(const TickStudyConfig& config, double feed_mm_s, bool with_step);
TickTestStage run_tick_test_stage(const TickStudyConfig& config, std::string& error);
// The outer loop's force poles for a pole set: the paper's (S3 Fig. 7)
// force-loop pair, mapped from z at 0.15 s to continuous time, times speedup.
fw::arsc::OuterPoles outer_poles(fw::arsc::PoleSet set, double speedup) noexcept;
// The arsc.* parameters of a study: its loop settings and the test stage's model.
fw::arsc::ArscSourceParams study_arsc_params(const TickStudyConfig& config, const TickTestStage& fit) noexcept;
TickStudyResult run_tick_study(const TickStudyConfig& config);

// --- shared by the study and its test stage (arsc_tick_study.cpp)
// The study's firmware config: planner limits, the force loop's parameters.
fw::FirmwareConfig study_firmware_config(const TickStudyConfig& config, const fw::arsc::ArscSourceParams& arsc);
class HilRig;
// Servo on and holding at config.start_mm (zero() of both axes), ready for a program.
std::unique_ptr<HilRig> ready_study_rig(const emu::Scenario& scenario, const fw::FirmwareConfig& firmware,
                                        const TickStudyConfig& config, std::string& error);
// The force the firmware sees, in N (its own conversion and scale).
double study_force_n(const fw::TickRecord& record, const fw::FirmwareConfig& firmware) noexcept;

}  // namespace tnv::hil
