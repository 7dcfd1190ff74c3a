// S4 (Lee 1983) in the loop: the firmware planner against the emulated
// boring process, judged on the true deflection. The paper's claims are
// targets; the thresholds below are the claims stated per seed (or as
// shares of seeds where a rare seed may miss), not our measured numbers.
#include <gtest/gtest.h>

#include <cmath>

#include "tools/hil/boring_direct_link.hpp"
#include "tools/hil/boring_sweep.hpp"

namespace tnv::hil {
namespace {

const BoringSegmentStats& segment(const BoringSweepResult& r, int first_part) {
  for (const BoringSegmentStats& s : r.segments)
    if (s.first_part == first_part) return s;
  ADD_FAILURE() << "no segment starting at part " << first_part;
  return r.segments.front();
}

// One shared sweep per claim set (CTest runs each TEST in its own process).
TEST(BoringClaims, Sigma16MicronsAlpha0HalfReproducesFigure3) {
  const BoringRunRequest request = paper_boring_request(0.016231, 0.5);
  const BoringSweepResult r = run_boring_sweep(request, 400);
  ASSERT_TRUE(r.error.empty()) << r.error;
  // "in band from part 2"
  const BoringSegmentStats& start = segment(r, 2);
  EXPECT_LE(start.bad_parts_mean, 0.05) << "bad parts per seed in parts 2-10 (band +-0.0487 mm)";
  EXPECT_GE(start.seeds_without_bad, 0.95);
  EXPECT_EQ(start.resets_mean, 0.0);
  // "after the large change at part 11: two to three bad parts and one reset"
  const BoringSegmentStats& large = segment(r, 11);
  EXPECT_GE(large.bad_parts_mean, 1.5);
  EXPECT_LE(large.bad_parts_mean, 3.0);
  EXPECT_GE(large.bad_parts_min, 1) << "part 11 itself cannot be helped";
  EXPECT_LE(large.bad_parts_max, 4);
  EXPECT_GE(large.seeds_with_one_reset, 0.95);
  EXPECT_GE(r.reset_fraction_by_part[10] + r.reset_fraction_by_part[11], 0.95) << "the reset comes at part 11 or 12";
  // "no reset and no bad part at the small change at part 21"
  const BoringSegmentStats& small = segment(r, 21);
  EXPECT_GE(small.seeds_without_bad, 0.98);
  EXPECT_GE(small.seeds_without_reset, 0.98);
  // Fig. 1's remark: the estimates are biased (alpha, beta high, C low) while the infeed is right.
  EXPECT_GT(start.alpha_error_end, 0.0);
  EXPECT_GT(start.beta_error_end, 0.0);
  EXPECT_LT(start.c_rel_error_end, 0.0);
}

TEST(BoringClaims, NoResetOverAThousandPartsOfAnUnchangedProcess) {
  BoringRunRequest request = paper_boring_request(0.016231, 0.5);
  request.parts = 1000;
  request.change_at = {};
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const BoringRunResult run = run_boring(request, seed);
    ASSERT_TRUE(run.error.empty()) << run.error;
    EXPECT_EQ(run.resets, 0) << "seed " << seed << ": false alarm";
    EXPECT_LE(run.bad_parts - 1, 2) << "seed " << seed << ": bad parts after part 1 (cut at S0) in 999 parts";
  }
}

// With alpha0 = 1 part 2 is cut before any RLS update, with
// S(L) = S0 d0 / d1(L); the true deflection is then d1^(1-alpha) d0^alpha
// whatever the estimator: out of band at both sigmas.
TEST(BoringClaims, WithAlpha0OnePartTwoIsBadForEveryGainForm) {
  for (fw::BoringGainForm form : {fw::BoringGainForm::normalised, fw::BoringGainForm::kalman, fw::BoringGainForm::printed}) {
    BoringRunRequest request = paper_boring_request(0.005, 1.0);
    request.process_sigma_mm = 0.0;  // exact gauge: the floor, not bad luck
    request.planner.gain_form = form;
    BoringDirectLink exact(false);  // doubles throughout: the identity below holds to round-off
    const BoringRunResult run = run_boring(request, 1, exact);
    ASSERT_TRUE(run.error.empty()) << run.error;
    const BoringPartRecord& p1 = run.parts[0];
    const BoringPartRecord& p2 = run.parts[1];
    for (std::size_t i = 0; i < 2; ++i) {
      const double expected = std::pow(p1.positions[i].true_deflection_mm, 1.0 - 0.5025) * std::pow(0.1165, 0.5025);
      EXPECT_NEAR(p2.positions[i].true_deflection_mm, expected, 1e-9) << fw::to_string(form);
      EXPECT_GT(p2.positions[i].true_deflection_mm - 0.1165, 3 * 0.005) << "mm";
    }
    EXPECT_GT(p2.positions[1].true_deflection_mm - 0.1165, 3 * 0.016231) << "bottom, mm";
    EXPECT_TRUE(p2.bad);
    EXPECT_TRUE(run.parts[10].bad) << "part 11: the large change";
  }
}

// The finding of docs/reproduction-s4.md at sigma_d = 0.005 mm,
// alpha0 = 1: the readings of (5)/(6) that are Kalman filters adapt too
// slowly after the small change at part 21 (no "three in a row" fires
// there), the printed form tracks it.
TEST(BoringClaims, Sigma5MicronsOnlyThePrintedGainFormTracksTheSmallChange) {
  BoringRunRequest request = paper_boring_request(0.005, 1.0);
  double bad_21[3] = {};
  double bad_total[3] = {};
  int i = 0;
  for (fw::BoringGainForm form : {fw::BoringGainForm::normalised, fw::BoringGainForm::kalman, fw::BoringGainForm::printed}) {
    request.planner.gain_form = form;
    const BoringSweepResult r = run_boring_sweep(request, 50);
    ASSERT_TRUE(r.error.empty()) << r.error;
    bad_21[i] = segment(r, 21).bad_parts_mean;
    bad_total[i] = r.bad_parts_mean;
    EXPECT_LE(r.reset_fraction_by_part[20] + r.reset_fraction_by_part[21], 0.2)
        << fw::to_string(form) << ": no immediate reset at the small change";
    ++i;
  }
  EXPECT_GE(bad_21[0], 4.0) << "normalised: bad parts in 21-30";
  EXPECT_GE(bad_21[1], 4.0) << "kalman: bad parts in 21-30";
  EXPECT_LE(bad_21[2], 2.0) << "printed: bad parts in 21-30 (part 21 itself is bad for any planner)";
  EXPECT_LT(bad_total[2], 0.7 * std::min(bad_total[0], bad_total[1]));
  EXPECT_GE(bad_total[2], 4.0) << "parts 1, 2, 11, 21 are bad for any estimator";
}

}  // namespace
}  // namespace tnv::hil
