// tnv-hil spindle-safety as a script runs it: the three numbers of the
// issue in its JSON and the verdict in the exit code.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/tools/cli_runner.hpp"

namespace tnv::test {
namespace {

TEST(SpindleSafetyCli, PrintsTransitionsSelfStartsAndFeedBeforeAtSpeed) {
  const CliRun r = run_tnv_hil("spindle-safety --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["transitions"].get<int>(), 7);
  EXPECT_EQ(j["self_starts"].get<int>(), 0);
  EXPECT_EQ(j["feed_before_at_speed"].get<int>(), 0);
  EXPECT_EQ(j["runs"].size(), 7u);
  EXPECT_TRUE(j["all_ok"].get<bool>());
}

TEST(SpindleSafetyCli, AnUnknownMachineIsExit2AndNothingRuns) {
  const CliRun r = run_tnv_hil("spindle-safety --scenario no-such-table");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty()) << r.out;
}

}  // namespace
}  // namespace tnv::test
