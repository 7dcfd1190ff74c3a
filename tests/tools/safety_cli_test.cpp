// tnv-hil faults and tnv-hil soak as a script runs them: exit codes and
// the JSON the docs quote.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/tools/cli_runner.hpp"

namespace tnv::test {
namespace {

TEST(SafetyCli, FaultsRunsOneCaseAndReportsTheBoardState) {
  const CliRun r = run_tnv_hil("faults --only dac_stuck --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["faults"].size(), 1u);
  const auto& row = j["faults"][0];
  EXPECT_EQ(row["latched"], "dac_error");
  EXPECT_EQ(row["ticks_to_detect"], 1);
  EXPECT_EQ(row["after_latch"]["dac_x"], 2048);
  EXPECT_EQ(row["after_latch"]["enable_x"], false);
  EXPECT_EQ(row["latching_tick"], row["fault_tick"]);
  EXPECT_TRUE(row["ok"].get<bool>());
  EXPECT_NEAR(j["watchdog"]["trip_after_last_kick_ms"].get<double>(), 3.01, 1e-6);
}

TEST(SafetyCli, FaultsRefusesAnUnknownCase) {
  const CliRun r = run_tnv_hil("faults --only melt");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("melt"), std::string::npos) << r.err;
}

TEST(SafetyCli, ShortSoakPassesAndSaysWhy) {
  const CliRun r = run_tnv_hil("soak --hours 0.05 --json");  // 180 s, 7 cycles
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_GE(j["simulated_s"].get<double>(), 180.0);
  EXPECT_EQ(j["missed_ticks"], 0);
  EXPECT_EQ(j["max_encoder_drift_counts"], 0);
  EXPECT_TRUE(j["stationary"].get<bool>());
  EXPECT_TRUE(j["passed"].get<bool>());
  EXPECT_GE(j["cycles"].size(), 6u);
}

TEST(SafetyCli, SoakRefusesACuttingScenarioWithNothingRun) {
  const CliRun r = run_tnv_hil("soak --hours 0.01 --scenario cut-900");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("cut"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

}  // namespace
}  // namespace tnv::test
