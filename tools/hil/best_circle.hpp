#pragma once
// The product's best circle configuration (issue 7, item 4) beside the
// papers' R-DVSC+DDC, on the four S1 scenarios, seed-averaged like table3.
// The best configuration is passed in (tnv-hil best-circle: R-DVSC+DDC with
// gains designed from the identified table plus its friction feed-forward);
// the papers' R-DVSC+DDC runs with the default config, its Table-3
// protocol, and table3 itself is untouched.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "firmware/tick/firmware_config.hpp"
#include "tools/hil/contour_stats.hpp"
#include "tools/hil/seed_sweep.hpp"

namespace tnv::hil {

// base with each axis' friction feed-forward set from friction[axis] and switched on
// (the papers' gains plus compensation only).
fw::FirmwareConfig with_friction_feedforward(const fw::FirmwareConfig& base,
                                             const std::array<fw::FrictionFeedForward, 2>& friction);

struct BestCircleRow {
  std::string scenario;
  ContourStats rdvsc{};  // the papers' R-DVSC+DDC, default config (Table 3's column)
  ContourStats best{};   // the best configuration
  std::string error;     // first failed run, if any
  SweepCell best_cell;   // with the seed-0 trace when asked
  SweepCell rdvsc_cell;
};

struct BestCircleRequest {
  std::vector<emu::Scenario> scenarios;  // e.g. no-cut, cut-900, cut-1200, cut-1500
  int seeds = 8;
  bool keep_seed0_trace = false;
  std::function<void(std::size_t, std::size_t)> progress;
};

std::vector<BestCircleRow> run_best_circle(const BestCircleRequest& request, const fw::FirmwareConfig& best);

}  // namespace tnv::hil
