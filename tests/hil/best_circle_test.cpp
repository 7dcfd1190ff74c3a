// Issue 7, item 4: the product's best circle configuration (identified on
// the emulated table, R-DVSC+DDC gains by the design rule, Coulomb friction
// feed-forward, the speed observer with the identified friction) on the
// reference no-cut circle, seed-averaged over 8 seeds exactly as the goal
// is stated, beside the papers' R-DVSC+DDC with its default config
// (Table 3's protocol).
//
// The goal: max <= 1.0 um and mean <= 0.15 um. Achieved when written:
// 0.8228 / 0.1416 / 0.1070 um (`tnv-hil best-circle --seeds 8`,
// docs/autotune.md), margins 18% on the max and 6% on the mean.
#include <gtest/gtest.h>

#include "emulator/scenario_file.hpp"
#include "tests/sanitized_build.hpp"
#include "tools/hil/best_circle.hpp"
#include "tools/hil/tune_identify.hpp"
#include "tools/tune/axis_design.hpp"

namespace tnv::hil {
namespace {

using namespace tnv::tune;

// The goal is an 8-seed average: a sanitizer build runs 2 and leaves the goal to the Release build.
constexpr int kBestCircleSeeds = tnv::test::kSanitizedBuild ? 2 : 8;

BestCircleRow run_no_cut() {
  const emu::Scenario no_cut = *emu::builtin_scenario("no-cut");
  std::array<AxisDesign, 2> d{};
  for (std::size_t i = 0; i < 2; ++i) {
    d[i] = design_axis(identify_axis_on_emulator(no_cut, hal::axis_from_index(i)));
    EXPECT_TRUE(d[i].ok) << d[i].error;
  }
  const fw::FirmwareConfig best = apply_designs(fw::default_firmware_config(), d[0], d[1]);
  EXPECT_TRUE(fw::validate(best).ok());
  BestCircleRequest request;
  request.scenarios = {no_cut};
  request.seeds = kBestCircleSeeds;
  const std::vector<BestCircleRow> rows = run_best_circle(request, best);
  EXPECT_EQ(rows.size(), 1u);
  return rows.empty() ? BestCircleRow{} : rows[0];
}

TEST(BestCircle, MeetsTheIssueGoalOnTheNoCutCircle) {
  const BestCircleRow r = run_no_cut();
  ASSERT_TRUE(r.error.empty()) << r.error;
  // The comparison is the papers' own: R-DVSC+DDC keeps its reversal glitch.
  EXPECT_GT(r.rdvsc.max_um, 2.0) << "papers' R-DVSC+DDC max " << r.rdvsc.max_um << " um";
  EXPECT_LT(r.best.std_um, 0.8 * r.rdvsc.std_um) << "best std " << r.best.std_um << " um vs " << r.rdvsc.std_um;
  if (tnv::test::kSanitizedBuild) return;  // the goal is stated on 8 seeds
  EXPECT_LE(r.best.max_um, 1.0) << "best configuration: max " << r.best.max_um << " um (" << kBestCircleSeeds
                                << "-seed average), goal <= 1.0 um";
  EXPECT_LE(r.best.mean_um, 0.15) << "best configuration: mean " << r.best.mean_um << " um (" << kBestCircleSeeds
                                  << "-seed average), goal <= 0.15 um";
}

}  // namespace
}  // namespace tnv::hil
