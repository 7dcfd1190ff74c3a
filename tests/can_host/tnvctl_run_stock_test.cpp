// tnvctl --emu run on a table with a stock: the machine's judgement of the
// cut (crashes, feed_before_at_speed) in the JSON, and a crash is exit 1.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/can_host/tnvctl_runner.hpp"

namespace tnv {
namespace {

// The stock's top 1 mm below the power-up tool point (nose -25 mm, tool 125 mm).
constexpr const char* kStock = "name = \"stock-1mm\"\n[stock]\nenabled = true\ntop_mm = -151.0\n";

TEST(TnvctlRunStock, ACutWithTheSpindleOnHasNoCrashAndNoFeedBeforeAtSpeed) {
  const auto state = test::state_dir("run_stock_cut");
  const auto scenario = test::write_file(state / "stock.toml", kStock);
  const auto prog = test::write_file(state / "cut.ngc", "G21 G91\nS3000 M3\nG1 Z-2 F300\nG1 X5 F600\nG0 Z2\nM5\nM2\n");
  const test::ToolRun r =
      test::tnvctl(state, "--emu --emu-scenario " + scenario.string() + " --json run " + prog.string() + " --no-score");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["crashes"].get<int>(), 0);
  EXPECT_EQ(j["feed_before_at_speed"].get<int>(), 0);
  EXPECT_GE(j["feed_onsets"].get<int>(), 1) << "the plunge (the cut follows it through the corner)";
  std::filesystem::remove_all(state);
}

TEST(TnvctlRunStock, FeedingIntoTheStockWithTheSpindleOffIsACrashAndExitOne) {
  const auto state = test::state_dir("run_stock_crash");
  const auto scenario = test::write_file(state / "stock.toml", kStock);
  const auto prog = test::write_file(state / "crash.ngc", "G21 G91\nG1 Z-2 F300\nG1 X5 F600\nG0 Z2\nM2\n");
  const test::ToolRun r =
      test::tnvctl(state, "--emu --emu-scenario " + scenario.string() + " --json run " + prog.string() + " --no-score");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_GE(j["crashes"].get<int>(), 1);
  EXPECT_FALSE(j["ok"].get<bool>());
  EXPECT_TRUE(test::has(j["error"].get<std::string>(), "crash")) << j["error"];
  std::filesystem::remove_all(state);
}

}  // namespace
}  // namespace tnv
