#pragma once
// Issue 8 item 5, second part: the robust ARSC at the tick on the emulated
// TNV-40 feed axis. The force loop (fw::arsc::OuterArsc) is an outer loop
// over the firmware: every period it reads the force (the I/O board's ADC,
// in the firmware's tick record) and the X feed, and sends the feed it
// wants as a jog-stream target (fw::TickTask::jog), which the firmware's
// R-DVSC+DDC position/speed loop follows. emu::Machine with [milling] on
// (the S3 force on X), the real FPGA driver, the emulated bus (HilRig).
//
// Before the cut a test-and-learning stage on a separate machine at the
// start depth drives the axis with a two-level feed and fits the outer
// loop's continuous-time model (force time constant, cutting gain, the
// axis' lag): it never reads the scenario's parameters.
#include <array>
#include <complex>
#include <cstdint>
#include <string>
#include <vector>

#include "emulator/scenario.hpp"
#include "firmware/adaptive/arsc/feed_force_model.hpp"
#include "firmware/adaptive/arsc/outer_gain_solve.hpp"
#include "firmware/adaptive/arsc/pole_sets.hpp"
#include "firmware/trajectory/jog_limits.hpp"

namespace tnv::hil {

struct TickStudyConfig {
  std::string label = "1 ms";
  std::uint32_t ticks_per_sample = 1;   // outer-loop period in 1 ms ticks (150 = the paper's 0.15 s)
  fw::arsc::PoleSet poles = fw::arsc::PoleSet::case1;
  double pole_speedup = 1.0;            // force-loop poles this many times faster than the paper's (continuous time)
  bool outer_loop = true;               // false: no force loop, a constant feed (the baseline)
  double constant_feed_mm_s = 20.0;     // the baseline's feed: about the loop's mean feed (same travel)
  double soft_start_s = 1.0;            // f* ramps from 0 to force_ref_n over this time
  double force_ref_n = 150.0;           // S3 experiment
  double feed_scale_mm_s = 10.0;        // normalisation inside the loop
  double memory_s = 0.15;               // estimator memory: lambda = exp(-T / memory_s)
  bool adapt = true;                    // false: the cutting gain estimate frozen at the test stage's (fixed gains)
  // Depth 0.2 -> 1.0 -> 0.2 mm over 5 + 5 s, then 0.5 s at 0.2 mm: at 150 N the table travels about
  // 210 mm, inside the firmware's +-250 mm soft limits from home (the paper's 15 + 15 s would need 600 mm).
  double duration_s = 10.5;
  double settle_s = 3.0;
  double test_stage_s = 4.0;
  fw::JogLimits jog{.speed_max_mm_s = 100.0, .accel_mm_s2 = 2000.0, .deadman_s = 0.1};  // deadman >= 2 periods
  emu::MillingParams milling{.enabled = true, .depth = {0.2, 1.0, 5.0, 5.0}};
};

// The test-and-learning stage's fit (continuous time, physical units).
struct TickTestStage {
  double force_time_constant_s = 0.0;
  double cutting_gain_n_per_mm_s = 0.0;  // G = K delta at the start depth
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
  double force_ref_n = 0.0;
  double feed_mm_s = 0.0;        // table speed (judge side)
  double command_mm_s = 0.0;     // the outer loop's feed command
  double cutting_gain_n_per_mm_s = 0.0;       // estimate
  double true_cutting_gain_n_per_mm_s = 0.0;  // K delta (judge side, for the plot)
};

struct TickStudyResult {
  TickStudyConfig config{};
  std::vector<TickStudyPoint> trace;  // every 10 ms
  TickTestStage test_stage{};
  double period_s = 0.0;
  double force_error_max_pct = 0.0;   // after settle_s, of force_ref_n, every tick
  double force_error_max_at_s = -1.0;
  double force_error_rms_pct = 0.0;
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
  std::uint32_t clamped_samples = 0;        // outer-loop command at the feed range's edge
  std::uint32_t samples = 0;
  std::uint32_t refused_updates = 0;        // gain designs refused (last good gains kept)
  std::uint32_t refused_jogs = 0;          // jog commands the firmware refused
  std::uint32_t deadman_stops = 0;          // jog streams the dead man stopped (the outer loop went quiet)
  double travel_mm = 0.0;
  double max_feed_mm_s = 0.0;
  fw::arsc::OuterPoles poles{};             // force-loop poles, rad/s
  std::array<std::complex<double>, 4> target_z{};  // all four closed-loop poles asked for, z at the period
  fw::arsc::OuterGains initial_gains{};     // at the test-stage model, normalised
  double max_abs_gain = 0.0;                // over the run, normalised
  std::string error;                        // set if the run could not start
};

emu::Scenario tick_study_scenario(const emu::MillingParams& milling);
TickTestStage run_tick_test_stage(const TickStudyConfig& config, std::string& error);
// The outer loop's force poles for a pole set: the paper's (S3 Fig. 7)
// force-loop pair, mapped from z at 0.15 s to continuous time, times speedup.
fw::arsc::OuterPoles outer_poles(fw::arsc::PoleSet set, double speedup) noexcept;
TickStudyResult run_tick_study(const TickStudyConfig& config);

}  // namespace tnv::hil
