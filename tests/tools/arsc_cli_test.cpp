// tnv-hil arsc as a script sees it: the issue's commands and JSON keys.
#include <gtest/gtest.h>

#include "tests/tools/cli_runner.hpp"
#include <sys/wait.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

namespace tnv {
namespace {

using test::CliRun;

using test::run_tnv_hil;

TEST(ArscCli, DesignPrintsTheSevenGainsOrSaysSingular) {
  CliRun r = run_tnv_hil("arsc design --poles case1 --json");
  ASSERT_EQ(r.exit_code, 0);
  nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["status"], "ok");
  for (const char* key : {"gamma01", "k", "gamma11", "gamma13", "gamma22", "gamma31", "gamma32"})
    EXPECT_TRUE(j["gains"].contains(key)) << key;
  EXPECT_LT(j["max_coefficient_error"].get<double>(), 1e-9);
  r = run_tnv_hil("arsc design --poles case2 --json");
  ASSERT_EQ(r.exit_code, 0);
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["status"], "singular");
  EXPECT_TRUE(j["gains"].is_null());
  EXPECT_NEAR(j["gamma01_eq25"].get<double>(), 0.6, 1e-12);
}

TEST(ArscCli, RunReportsTheIssueKeysAndTheTrace) {
  const CliRun r = run_tnv_hil("arsc run --poles case4 --variant robust --json");
  ASSERT_EQ(r.exit_code, 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_LT(j["force_error_max_pct"].get<double>(), 10.0);
  EXPECT_GE(j["force_error_rms_pct"].get<double>(), 0.0);
  EXPECT_FALSE(j["diverged"].get<bool>());
  ASSERT_EQ(j["trace"].size(), 201u);
  for (const char* key : {"t_s", "feed", "force", "u", "gains", "cutting_gain_estimate"})
    EXPECT_TRUE(j["trace"][100].contains(key)) << key;
}

TEST(ArscCli, TickAtOnePeriodReportsErrorPeriodAndSaturation) {
  const CliRun r = run_tnv_hil("arsc tick --period-ms 1 --speedup 4 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_DOUBLE_EQ(j["period_s"].get<double>(), 0.001);
  EXPECT_LT(j["force_error_max_pct"].get<double>(), 1.0);
  EXPECT_GE(j["force_error_rms_pct"].get<double>(), 0.0);
  EXPECT_FALSE(j["diverged"].get<bool>());
  for (const char* key : {"dac_saturated_ticks", "dac_saturated_fraction", "dac_saturated_longest_s",
                          "first_dac_saturation_s", "command_clamped_samples", "command_clamped_after_settle",
                          "test_stage", "initial_gains", "arsc_params", "program", "accel_ratio_max",
                          "jerk_ratio_max", "override_min_seen", "override_max_seen", "refused_segments"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["path"], "line");
  EXPECT_EQ(j["arsc_params"]["period_ticks"].get<int>(), 1);
  EXPECT_TRUE(j["arsc_params"]["enable"].get<bool>());
  EXPECT_LE(j["jerk_ratio_max"].get<double>(), 1.0 + 1e-6);
}

TEST(ArscCli, TickOnTheArcPathTurnsAndHoldsTheForce) {
  const CliRun r = run_tnv_hil("arsc tick --period-ms 1 --speedup 4 --path arc --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["path"], "arc");
  EXPECT_LT(j["force_error_max_pct"].get<double>(), 1.0);
  EXPECT_LT(j["travel_x_mm"].get<double>(), j["travel_mm"].get<double>() - 20.0) << "part of the path is not along X";
}

TEST(ArscCli, TickOnAStockStepReportsTheForceOneSecondAfterTheStepPerSeed) {
  const CliRun r = run_tnv_hil("arsc tick --path stock-step --period-ms 1 --seeds 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["runs"].size(), 2u);
  for (const nlohmann::json& run : j["runs"]) {
    EXPECT_EQ(run["path"], "stock-step");
    const nlohmann::json& k = run["stock_step"];
    EXPECT_EQ(k["crashes"].get<int>(), 0);
    EXPECT_NEAR(k["depth_after_mm"].get<double>(), 2.0, 0.01);
    EXPECT_LT(k["force_error_pct"].get<double>(), 10.0) << "issue 27's goal";
    EXPECT_GT(k["step_at_s"].get<double>(), 3.0);
  }
  const CliRun text = run_tnv_hil("arsc tick --path stock-step --period-ms 1");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("1.0 s after: force error"), std::string::npos) << text.out;
  EXPECT_EQ(run_tnv_hil("arsc tick --path stock-step --step-ramp-mm 4").exit_code, 2) << "--step-ramp-mm needs --period-ms";
}

TEST(ArscCli, TickWithoutAPeriodComparesTheRates) {
  const CliRun r = run_tnv_hil("arsc tick --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["runs"].size(), 6u);
  EXPECT_FALSE(j["runs"][0]["outer_loop"].get<bool>());
  double slow = -1.0, fast = -1.0;
  for (const auto& run_j : j["runs"]) {
    if (!run_j["outer_loop"].get<bool>()) continue;
    if (run_j["period_ms"].get<double>() == 150.0 && run_j["pole_speedup"].get<double>() == 1.0)
      slow = run_j["force_error_max_pct"].get<double>();
    if (run_j["period_ms"].get<double>() == 1.0 && run_j["pole_speedup"].get<double>() == 1.0)
      fast = run_j["force_error_max_pct"].get<double>();
  }
  ASSERT_GT(slow, 0.0);
  ASSERT_GT(fast, 0.0);
  EXPECT_LT(fast, slow);
}

TEST(ArscCli, BadArgumentsAreExitCode2) {
  EXPECT_EQ(run_tnv_hil("arsc run --poles case5 --variant robust").exit_code, 2);
  EXPECT_EQ(run_tnv_hil("arsc run --poles case1 --variant literal").exit_code, 2);
  EXPECT_EQ(run_tnv_hil("arsc design").exit_code, 2);
  EXPECT_EQ(run_tnv_hil("arsc tick --period-ms 0").exit_code, 2);
  EXPECT_EQ(run_tnv_hil("arsc tick --poles case9").exit_code, 2);
  EXPECT_EQ(run_tnv_hil("arsc tick --period-ms 1 --speedup -2").exit_code, 2);
  EXPECT_EQ(run_tnv_hil("arsc tick --speedup 4").exit_code, 2);  // only with --period-ms
  // The bench options: an unknown table is named and nothing runs; --seeds needs --scenario.
  const CliRun unknown = run_tnv_hil("arsc compare --scenario no-such-table");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_TRUE(unknown.out.empty()) << unknown.out;
  EXPECT_NE(unknown.err.find("no-such-table"), std::string::npos) << unknown.err;
  EXPECT_EQ(run_tnv_hil("arsc compare --seeds 4").exit_code, 2);
  EXPECT_EQ(run_tnv_hil("arsc tick --scenario no-such-table").exit_code, 2);
  EXPECT_EQ(run_tnv_hil("arsc tick --path circle").exit_code, 2);
}

}  // namespace
}  // namespace tnv
