#pragma once
// Each tnv-hil command family registers its subcommands here. A
// subcommand's callback sets `run`; main() calls it after parsing.
#include <CLI/CLI.hpp>

#include "tools/tnv-hil/cli_support.hpp"

namespace tnv::cli {

void add_circle_commands(CLI::App& app, Runner& run);  // circle, table3, plant-check (S1)
void add_fault_commands(CLI::App& app, Runner& run);   // faults (safety: fault injection)
void add_soak_commands(CLI::App& app, Runner& run);    // soak (safety: long run)
void add_boring_commands(CLI::App& app, Runner& run);  // boring (S4)
void add_arsc_commands(CLI::App& app, Runner& run);    // arsc design | run | compare | tick (S3)
void add_shaper_commands(CLI::App& app, Runner& run);  // shaper design | move | jog | grid (S2)
void add_best_circle_commands(CLI::App& app, Runner& run);  // best-circle, identify (issue 7)
void add_rt_budget_commands(CLI::App& app, Runner& run);    // rt-budget (CAN service cost on the real-time loop)
void add_bus_stress_commands(CLI::App& app, Runner& run);   // bus-stress (safety: CAN priority, tags, hosts)
void add_path_commands(CLI::App& app, Runner& run);         // path (G-code programs, docs/motion.md)
void add_homing_commands(CLI::App& app, Runner& run);       // homing (home switch and index, docs/safety.md)
void add_spindle_commands(CLI::App& app, Runner& run);      // spindle-safety (docs/safety.md "Spindle")
void add_screw_commands(CLI::App& app, Runner& run);
#ifdef TNV_HAVE_CAMPAIGN
void add_campaign_commands(CLI::App& app, Runner& run);  // campaign plan | run | merge | replay | report
#endif
void add_freq_response_commands(CLI::App& app, Runner& run);  // freq-response (issue 17, over the emulated CAN node)        // screw-map, screw-fit (lead-error table)

}  // namespace tnv::cli
