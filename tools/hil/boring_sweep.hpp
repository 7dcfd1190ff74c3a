#pragma once
// run_boring() over seeds 1..N, with the statistics the S4 claims are
// stated in: bad parts and resets per run and per segment of the run
// (part 1 at S0; up to the first change; between the changes; after).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tools/hil/boring_run.hpp"

namespace tnv::hil {

struct BoringSegmentStats {
  int first_part = 0;
  int last_part = 0;
  double bad_parts_mean = 0.0;
  int bad_parts_min = 0;
  int bad_parts_max = 0;
  double resets_mean = 0.0;
  double seeds_without_bad = 0.0;   // fraction of seeds
  double seeds_without_reset = 0.0;
  double seeds_with_one_reset = 0.0;
  // Estimates after the segment's last part, seed means: C_hat / C - 1,
  // alpha_hat - alpha, beta_hat - beta (and their absolute values).
  double c_rel_error_end = 0.0, alpha_error_end = 0.0, beta_error_end = 0.0;
  double c_rel_abs_error_end = 0.0, alpha_abs_error_end = 0.0, beta_abs_error_end = 0.0;
};

struct BoringSweepResult {
  std::string planner;  // where it ran (BoringPlannerLink::describe())
  int seeds = 0;
  std::uint64_t first_seed = 1;  // seeds first_seed .. first_seed + seeds - 1
  double bad_parts_mean = 0.0;  // parts 1..N
  int bad_parts_max = 0;
  double resets_mean = 0.0;
  double deflection_rms_mean_mm = 0.0;
  std::vector<double> bad_fraction_by_part;    // index part - 1
  std::vector<double> reset_fraction_by_part;
  std::vector<BoringSegmentStats> segments;
  std::vector<int> bad_parts_per_seed;
  std::vector<int> resets_per_seed;
  BoringRunResult seed1;  // the first seed's run
  std::string error;  // first failed seed
};

using BoringProgress = std::function<void(std::size_t, std::size_t)>;

// Throws std::invalid_argument for an invalid request or seeds < 1. Every
// seed starts the planner afresh through `planner`.
BoringSweepResult run_boring_sweep(const BoringRunRequest& request, int seeds, BoringPlannerLink& planner,
                                   const BoringProgress& progress = {});
// With the planner in this process at the node's resolution (BoringDirectLink).
BoringSweepResult run_boring_sweep(const BoringRunRequest& request, int seeds, const BoringProgress& progress = {});
// Each seed run by `run_seed` (the same statistics; e.g. every part cut on
// the emulated machine: tools/can_emu/boring_machine_run.hpp); `planner`
// names where the planner ran. Seeds first_seed .. first_seed + seeds - 1
// (a long sweep split over processes; first_seed >= 1).
using BoringSeedRun = std::function<BoringRunResult(std::uint64_t seed)>;
BoringSweepResult run_boring_sweep(const BoringRunRequest& request, int seeds, const std::string& planner,
                                   const BoringSeedRun& run_seed, const BoringProgress& progress = {},
                                   std::uint64_t first_seed = 1);

}  // namespace tnv::hil
