// Issue 27, "S3 on a real cut": the robust ARSC as the firmware's feed-
// override source while a program mills the emulator's stock where the
// tool is ([stock] on, the spindle at 6000 rpm) and steps down in Z inside
// the cut, so a_p steps 1 -> 2 mm (2:1). The goal: the force within +-10 %
// of f* 1 s after the step. Judged on the emulator's milling force (and as
// the force ADC read it), from the tick a_p leaves the start depth, over
// several seeded tables; a constant feed misses it (the force doubles and
// more, F ~ a_p f_z^0.75).
#include <gtest/gtest.h>

#include <string>

#include "tests/sanitized_build.hpp"
#include "tools/hil/arsc_tick_study.hpp"
#include "tools/hil/seeded_scenario.hpp"

namespace tnv::hil {
namespace arsc_tick_stock_step_test {
namespace {

// Every seed meets the goal on its own: a sanitizer build runs the first.
constexpr int kSeeds = tnv::test::kSanitizedBuild ? 1 : 3;

TickStudyConfig stock_step(std::uint32_t ticks, double speedup, int seed) {
  TickStudyConfig c;
  c.path = StudyPath::stock_step;
  c.ticks_per_sample = ticks;
  c.pole_speedup = speedup;
  c.table = seeded(emu::Scenario{}, seed);
  return c;
}

void expect_goal_met(const TickStudyResult& r, const std::string& what) {
  ASSERT_TRUE(r.error.empty()) << what << ": " << r.error;
  EXPECT_FALSE(r.diverged) << what;
  EXPECT_TRUE(r.fault.empty()) << what << ": " << r.fault;
  EXPECT_EQ(r.crashes, 0u) << what;
  EXPECT_LT(r.program_end_s, 0.0) << what << ": the program ran out";
  ASSERT_GT(r.step_at_s, r.config.settle_s) << what << ": the step comes after the loop settled";
  EXPECT_NEAR(r.depth_before_mm, 1.0, 0.02) << what;
  EXPECT_NEAR(r.depth_after_mm, 2.0, 0.01) << what << ": Z holds its depth within its following error";
  EXPECT_LT(r.feed_after_mm_s, 0.8 * r.feed_before_mm_s) << what << ": the loop must slow the feed for the deeper cut";
  EXPECT_LT(r.step_error_pct, 10.0) << what << ": force error 1 s after the step, % of f*";
  EXPECT_LT(r.step_error_measured_pct, 10.0) << what;
  EXPECT_LT(r.after_step_max_pct, 10.0) << what << ": worst from 1 s after the step on";
  EXPECT_LE(r.accel_ratio_max, 1.0 + 1e-6) << what;
  EXPECT_LE(r.jerk_ratio_max, 1.0 + 1e-6) << what;
  std::printf("%s: step at %.3f s, 1 s after %.3f %% (ADC %.3f %%), worst after %.3f %%, feed %.2f -> %.2f mm/s\n",
              what.c_str(), r.step_at_s, r.step_error_pct, r.step_error_measured_pct, r.after_step_max_pct,
              r.feed_before_mm_s, r.feed_after_mm_s);
}

TEST(ArscTickStockStep, TheOneMsLoopHoldsTheForceOneSecondAfterA2To1DepthStep) {
  for (int seed = 0; seed < kSeeds; ++seed) {
    const TickStudyResult r = run_tick_study(stock_step(1, 1.0, seed));
    expect_goal_met(r, "1 ms, seed " + std::to_string(seed));
    // Before the step too: the loop holds a_p = 1 mm steadily (the 4x poles do not: docs/reproduction-s3.md).
    EXPECT_EQ(r.clamped_after_settle, 0u);
  }
}

TEST(ArscTickStockStep, ThePapersRateMeetsTheGoalToo) {
  for (int seed = 0; seed < kSeeds; ++seed) {
    const TickStudyResult r = run_tick_study(stock_step(150, 1.0, seed));
    expect_goal_met(r, "0.15 s, seed " + std::to_string(seed));
  }
}

TEST(ArscTickStockStep, AConstantFeedMissesTheForceAfterTheStep) {
  TickStudyConfig c = stock_step(1, 1.0, 0);
  c.outer_loop = false;
  const TickStudyResult r = run_tick_study(c);
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.crashes, 0u);
  ASSERT_GT(r.step_at_s, 0.0);
  EXPECT_GT(r.step_error_pct, 80.0) << "20 mm/s at a_p 2 mm is 2 x 150 N";
}

}  // namespace
}  // namespace arsc_tick_stock_step_test
}  // namespace tnv::hil
