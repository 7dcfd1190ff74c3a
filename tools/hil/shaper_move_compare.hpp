#pragma once
// The same point-to-point move unshaped and shaped, over several encoder
// phases (scenario seeds, seeded_scenario.hpp). At standstill the table
// stick-slips by about one encoder count now and then (the holding limit
// cycle of the loop on a stiction plant); each slip rings the structural
// mode at the ~1 um level, which is the size of the settling band. Single
// runs are therefore noisy in settling time; the comparison is made per
// seed and summarised by the median.
#include <optional>
#include <vector>

#include "tools/hil/shaper_move_run.hpp"

namespace tnv::hil {

struct MovePair {
  int seed = 0;
  MoveRunResult unshaped;
  MoveRunResult shaped;
  double residual_ratio() const noexcept;  // shaped / unshaped peak-to-peak
  // unshaped / shaped settling time; nullopt when the shaped run never
  // settled; +inf-like large when only the unshaped never did.
  std::optional<double> settling_ratio() const noexcept;
};

struct MoveComparison {
  std::vector<MovePair> pairs;  // seed order
  std::string error;            // first run that did not complete
  double median_residual_ratio = 0.0;
  double worst_residual_ratio = 0.0;
  double median_settling_ratio = 0.0;  // a shaped run that never settled counts as ratio 0
  double median_unshaped_residual_um = 0.0;
  double median_shaped_residual_um = 0.0;
  std::optional<double> median_unshaped_settling_s;
  std::optional<double> median_shaped_settling_s;
};

// request.shaper is the shaper of the shaped runs; the unshaped runs drop it.
// Trace kept for seed 0 when request.keep_trace.
MoveComparison compare_move(const MoveRunRequest& request, const fw::FirmwareConfig& base_config, int seeds);

}  // namespace tnv::hil
