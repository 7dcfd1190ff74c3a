#pragma once
// The product's best circle configuration (issue 7, item 4) beside the
// papers' R-DVSC+DDC, on the four S1 scenarios, seed-averaged like table3.
// The best configuration is passed in (tnv-hil best-circle: R-DVSC+DDC with
// gains designed from the identified table plus its friction feed-forward
// and speed observer);
// the papers' R-DVSC+DDC runs with the default config, its Table-3
// protocol, and table3 itself is untouched. design_best_config /
// run_table_check do the same on a table the rules were not tuned on
// (tnv-hil best-circle --scenario; docs/autotune.md section 4).
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "emulator/scenario.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tools/hil/seed_sweep.hpp"
#include "tools/hil/tune_identify.hpp"
#include "tools/score/contour_stats.hpp"
#include "tools/tune/axis_design.hpp"

namespace tnv::hil {

// base with the circle's plane axes' friction feed-forward set from
// friction[0] (hal::kPlaneFirst) and friction[1] (hal::kPlaneSecond) and
// switched on (the papers' gains plus compensation only); any other axis
// keeps base's.
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

// How the best configuration is made from an identified table (the flags of
// tnv-hil best-circle); the defaults are the rule of tools/tune/axis_design.hpp.
enum class BestGains { autotune, papers };       // designed from the table | S1 Tables 1/2
enum class BestFeedForward { coulomb, stribeck, off };
enum class BestObserverUse { speed, position, off };

struct BestConfigChoice {
  BestGains gains = BestGains::autotune;
  BestFeedForward ff = BestFeedForward::coulomb;
  double ff_fraction = 1.0;
  BestObserverUse observer = BestObserverUse::speed;
  double observer_sigma_v_mm_s = tune::kObserverSpeedNoise_mm_s;
  double observer_sigma_d_mm_s = tune::kObserverDisturbanceNoise_mm_s;
  bool observer_friction = true;  // the identified f_c / K in the observer's model
};

struct BestConfigDesign {
  bool ok = false;
  bool bad_input = false;  // the choice itself is refused (no stable observer, config invalid)
  std::string error;       // one line, names the axis / field
  std::array<tune::AxisIdentification, 2> identified{};
  std::array<tune::AxisDesign, 2> designs{};
  fw::FirmwareConfig config{};
};

// Identifies both axes of `table` with the spindle off (cutting and milling
// disabled, as docs/autotune.md asks; the reference no-cut table is
// unchanged by that), designs from them and applies `choice`. Validated.
BestConfigDesign design_best_config(const emu::Scenario& table, const BestConfigChoice& choice);

// `best` with the speed observer switched off on both axes (everything else kept).
fw::FirmwareConfig without_observer(const fw::FirmwareConfig& best);

// One table the best configuration was not tuned on: the S1 circle on it,
// seed-averaged, for the papers' R-DVSC+DDC (default config), the best
// configuration, and the best configuration with its observer off.
struct TableCheckRow {
  std::string scenario;
  ContourStats rdvsc{};
  ContourStats best{};
  ContourStats observer_off{};
  std::string error;  // first failed run ("<config>: seed N: ..."), empty when every run completed fault-free
  SweepCell rdvsc_cell;
  SweepCell best_cell;
  SweepCell observer_off_cell;
};

struct TableCheckRequest {
  emu::Scenario table;
  int seeds = 8;
  bool keep_seed0_trace = false;
  std::function<void(std::size_t, std::size_t)> progress;  // (done, 3 * seeds)
};

TableCheckRow run_table_check(const TableCheckRequest& request, const fw::FirmwareConfig& best);

}  // namespace tnv::hil
