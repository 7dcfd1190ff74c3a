#pragma once
// Issue 8 item 5, second part: the robust ARSC on the emulated TNV-40 X
// axis (emu::Machine with [milling] on: the S3 force process, the force on
// the I/O board's ADC), through the real FPGA driver, at a chosen ARSC
// period: 1 ms (every tick) or 0.15 s (every 150th tick, as in the paper).
// The ARSC output is the X speed command (the DAC), as the paper's servo
// motor input; feed = encoder position difference over the ARSC period;
// force = ADC code / volts per N. The control computed at one ARSC sample
// is written at the next (the same one-sample delay as the design model).
// Before the cut a test-and-learning stage on a separate machine at the
// start depth fits the drive and the force pole. fw::TickTask is not used
// (it runs the circle experiment only); this is the loop a tick would run.
#include <cstdint>
#include <string>
#include <vector>

#include "emulator/scenario.hpp"
#include "firmware/adaptive/arsc/pole_sets.hpp"
#include "tools/hil/arsc_test_stage.hpp"

namespace tnv::hil {

struct TickStudyConfig {
  std::string label = "1 ms";
  std::uint32_t ticks_per_sample = 1;   // ARSC period in 1 ms ticks (150 = the paper's 0.15 s)
  fw::arsc::PoleSet poles = fw::arsc::PoleSet::case1;
  double pole_speedup = 1.0;            // continuous-time poles this many times faster than the paper's
  // false: six of the seven paper poles, mapped to the ARSC period (as at 0.15 s).
  // true: the delay state's pole stays at 0 and the drive's at its identified place; four of the
  //       paper poles (mapped) shape the force loop; gamma03 (a compensator pole) is mapped too.
  bool keep_fast_poles = false;
  double soft_start_s = 1.0;            // f* ramps from 0 to force_ref_n over this time
  double force_ref_n = 150.0;           // S3 experiment
  double feed_ref_mm_s = 10.0;          // normalisation of feed and command
  double memory_s = 0.15;               // estimator memory: lambda = exp(-T / memory_s)
  double duration_s = 12.0;
  double settle_s = 3.0;
  double test_stage_s = 15.0;
  emu::MillingParams milling{.enabled = true, .depth = {0.2, 1.0, 6.0, 6.0}};
};

struct TickStudyPoint {
  double t_s = 0.0;
  double depth_mm = 0.0;
  double force_n = 0.0;     // measured (ADC)
  double feed_mm_s = 0.0;   // table speed (truth)
  double command_mm_s = 0.0;
  double cutting_gain = 0.0;  // g^ (normalised)
};

struct TickStudyResult {
  TickStudyConfig config{};
  std::vector<TickStudyPoint> trace;  // every 10 ms
  TestStageFit test_stage{};          // normalised, per ARSC period
  double force_error_max_pct = 0.0;   // after settle_s, of force_ref_n, every tick
  double force_error_rms_pct = 0.0;
  bool diverged = false;
  double travel_mm = 0.0;
  std::uint32_t refused_updates = 0;
  double initial_gamma01 = 0.0;       // of the design at the identified model
  double initial_max_abs_gain = 0.0;  // largest |k, gamma11, gamma13, gamma22, gamma31, gamma32|
  double first_saturation_s = -1.0;   // first time the command hit the DAC range (-1: never)
  std::string error;                  // set if the run could not start
};

emu::Scenario tick_study_scenario(const emu::MillingParams& milling);
TickStudyResult run_tick_study(const TickStudyConfig& config);

}  // namespace tnv::hil
