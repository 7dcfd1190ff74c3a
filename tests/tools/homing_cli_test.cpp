// tnv-hil homing as a script runs it: the goal's verdict in the exit code,
// the same cycle on a bench table (backlash, lead error, noise, transport),
// and a bad table refused before anything runs.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/tools/cli_runner.hpp"

namespace tnv::test {
namespace {

TEST(HomingCli, HomesOnTheBenchTableWithinTheGoalAndSaysWhichTable) {
  const CliRun r = run_tnv_hil("homing --seeds 3 --scenario bench-no-cut --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["scenario"], "bench-no-cut");
  EXPECT_TRUE(j["all_homed"].get<bool>());
  EXPECT_LE(j["home_error_um_max"].get<double>(), 0.5);
  EXPECT_EQ(j["runs"].size(), 3u);
}

TEST(HomingCli, AnUnknownTableIsExit2AndNothingRuns) {
  const CliRun r = run_tnv_hil("homing --seeds 1 --scenario no-such-table");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_NE(r.err.find("no-such-table"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace tnv::test
