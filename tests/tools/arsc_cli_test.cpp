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

CliRun run(const std::string& args) { return test::run_tnv_hil(args); }

TEST(ArscCli, DesignPrintsTheSevenGainsOrSaysSingular) {
  CliRun r = run("arsc design --poles case1 --json");
  ASSERT_EQ(r.exit_code, 0);
  nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["status"], "ok");
  for (const char* key : {"gamma01", "k", "gamma11", "gamma13", "gamma22", "gamma31", "gamma32"})
    EXPECT_TRUE(j["gains"].contains(key)) << key;
  EXPECT_LT(j["max_coefficient_error"].get<double>(), 1e-9);
  r = run("arsc design --poles case2 --json");
  ASSERT_EQ(r.exit_code, 0);
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["status"], "singular");
  EXPECT_TRUE(j["gains"].is_null());
  EXPECT_NEAR(j["gamma01_eq25"].get<double>(), 0.6, 1e-12);
}

TEST(ArscCli, RunReportsTheIssueKeysAndTheTrace) {
  const CliRun r = run("arsc run --poles case4 --variant robust --json");
  ASSERT_EQ(r.exit_code, 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_LT(j["force_error_max_pct"].get<double>(), 10.0);
  EXPECT_GE(j["force_error_rms_pct"].get<double>(), 0.0);
  EXPECT_FALSE(j["diverged"].get<bool>());
  ASSERT_EQ(j["trace"].size(), 201u);
  for (const char* key : {"t_s", "feed", "force", "u", "gains", "cutting_gain_estimate"})
    EXPECT_TRUE(j["trace"][100].contains(key)) << key;
}

TEST(ArscCli, BadArgumentsAreExitCode2) {
  EXPECT_EQ(run("arsc run --poles case5 --variant robust").exit_code, 2);
  EXPECT_EQ(run("arsc run --poles case1 --variant literal").exit_code, 2);
  EXPECT_EQ(run("arsc design").exit_code, 2);
}

}  // namespace
}  // namespace tnv
