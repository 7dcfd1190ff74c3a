#pragma once
// tnv-hil spindle-safety (issue 27, docs/safety.md "Spindle"): every
// transition after which a spindle must not start by itself, driven on the
// emulated machine with the real firmware and FPGA driver, judged from the
// emulator's truth (the spindle drive's real speed, the table's real
// speed), never from the firmware's own record.
//
// Each transition runs on a fresh machine: the spindle is started and a
// program of feed moves runs with it; then the transition (feed hold with
// the spindle stopped in it and resumed, abort, fault and its clear,
// e-stop and its release, host timeout and its return, node restart,
// parameter load) and 3 s of watching; then a new start and a second
// program, which must wait for the spindle again and whose end stops it.
//  - self_starts: the spindle's real speed rose (by more than
//    kSelfStartRpm above its lowest since it was stopped) without a start;
//  - feed_before_at_speed: a feed move began while the spindle was
//    commanded on and not at speed, as tools/hil/feed_start_judge.hpp
//    judges it for tnv-hil path and tnvctl --emu run (the tool's real speed
//    past 0.5 mm/s from rest and then 10 um from where it was; the drive's
//    command steady and its real speed within 5 % or 20 rpm of it). The
//    programs have feed moves only, at 3 mm/s.
#include <cstdint>
#include <string>
#include <vector>

#include "emulator/scenario.hpp"
#include "firmware/spindle/spindle_params.hpp"

namespace tnv::hil {

inline constexpr double kSelfStartRpm = 10.0;

struct SpindleTransitionResult {
  std::string name;
  std::string stop_cause;        // what the firmware recorded for the stop the transition made ("" if none)
  bool stopped = false;          // the spindle came to rest (|n| < 1 rpm) after the transition
  bool self_start = false;
  double rise_rpm = 0.0;         // the most the real speed rose above its lowest while it was off
  bool refused_while_turning = false;  // param_load: the load was refused while the spindle turned (n/a: true)
  bool restarted = false;        // the new start brought it to speed
  bool program_end_stop = false; // the second program's end stopped it (cause program_end, at rest)
  std::uint32_t feed_onsets = 0;
  std::uint32_t feed_before_at_speed = 0;
  bool ok() const noexcept {
    return stopped && !self_start && refused_while_turning && restarted && program_end_stop &&
           feed_before_at_speed == 0 && feed_onsets >= 1;
  }
};

struct SpindleSafetySummary {
  std::vector<SpindleTransitionResult> transitions;
  std::uint32_t self_starts = 0;
  std::uint32_t feed_before_at_speed = 0;
  std::uint32_t feed_onsets = 0;
  bool all_ok = false;
};

// The transitions' names, in the order they run.
const std::vector<std::string>& spindle_transition_names();

// `firmware_spindle`: the firmware's spindle.* parameters (the judge keeps
// the default at-speed window, 5 % or 20 rpm, whatever the firmware uses).
SpindleSafetySummary run_spindle_safety(const emu::Scenario& scenario, const fw::SpindleParams& firmware_spindle = {});

}  // namespace tnv::hil
