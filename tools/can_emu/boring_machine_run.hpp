#pragma once
// S4 through real motion (issue 27): every part is a boring pass on the
// emulated machine. The emulated node (EmulatedBus: the real firmware's
// tick and CAN node) gets the part's program (tools/hil/boring_pass_program.hpp:
// the spindle on and at speed, Z feeding down through the bore at the
// infeeds its S4 planner told in BORE_INFEED) and runs it; the machine's
// boring bar ([boring], emulator/boring_pass.hpp) deflects with the
// overhang and the infeed per revolution it really sees; after the part
// its gauge reads the bore at the two depths and the readings go back to
// the node in BORE_GAUGE. Parts are judged, as in process, on the true
// deflection at the gauge depths (bad: outside d0 +- 3 sigma_d).
#include <cstdint>
#include <functional>
#include <string>

#include "emulator/machine.hpp"
#include "emulator/scenario.hpp"
#include "tools/hil/boring_run.hpp"
#include "tools/hil/boring_sweep.hpp"

namespace tnv::can_host {

struct BoringMachineOptions {
  double spindle_rpm = 6000.0;  // the passes' S: the feed F = S n (mm/min); part 1 (S0 0.5 mm/rev) runs at 50 mm/s
  // true: every feed line a feed per revolution on the node (Z at S times the measured spindle speed);
  // false: G94 at F = S n from the commanded speed, converted here (as before the node fed per revolution).
  bool feed_per_rev = true;
  // With feed_per_rev: true, the pass is one feed line along the depth whose infeed the node takes from its
  // planner's schedule at the bar's overhang every tick (hil::boring_pass_depth_gcode); false, ~10 mm segments
  // each at the host's S(L) at its middle (hil::boring_pass_segments).
  bool along_depth = true;
  // Called after every step of the emulated machine (a judge watching the bar's truth); empty = none.
  std::function<void(const emu::Machine&)> on_step{};
  // > 0: the emulated spindle drive's K_sp (rpm at full scale) instead of the reference plant's 12,000, and the
  // node's at-speed window this wide (spindle.at_speed_fraction): a spindle that turns slower than its command
  // and is still at speed, as one drooping under load.
  double drive_rpm_at_full_scale = 0.0;
  double at_speed_fraction = 0.0;  // > 0: the node's spindle.at_speed_fraction for the run
};

// The machine a request is cut on: the default machine with its stock on,
// the boring bar on it ([boring] enabled) and the request's process
// (sigma_d, change parts) and bench gauge.
emu::Scenario boring_machine_scenario(const hil::BoringRunRequest& request);

// "" if the request can run on the machine, else "field: reason": the
// node's planner (hil::node_planner_refusal), two measuring overhangs that
// are the scenario's gauge depths (L0 + depth), the pass within Z's travel.
std::string boring_machine_refusal(const hil::BoringRunRequest& request, const BoringMachineOptions& options);

// One seed: a fresh emulated node and machine (hil::seeded(scenario, seed)),
// its planner started afresh, request.parts passes. Throws
// std::invalid_argument when boring_machine_refusal() says why; a node or
// a pass that fails ends the run with result.error set (the parts so far kept).
hil::BoringRunResult run_boring_on_machine(const hil::BoringRunRequest& request, std::uint64_t seed,
                                           const BoringMachineOptions& options);

// Seeds first_seed .. first_seed + N - 1 (statistics as run_boring_sweep).
hil::BoringSweepResult run_boring_sweep_on_machine(const hil::BoringRunRequest& request, int seeds,
                                                   const BoringMachineOptions& options,
                                                   const hil::BoringProgress& progress = {},
                                                   std::uint64_t first_seed = 1);

}  // namespace tnv::can_host
