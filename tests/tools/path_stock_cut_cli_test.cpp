// tnv-hil path on a machine with a stock, as a script runs it: crashes and
// feed_before_at_speed in the JSON and the text, and a crash is exit 1.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "tests/tools/cli_runner.hpp"

namespace tnv::test {
namespace {

std::string temp_file(const std::string& name, const std::string& text) {
  const std::filesystem::path p =
      std::filesystem::temp_directory_path() / ("tnv_stockcut_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(p) << text;
  return p.string();
}

// The stock's top 1 mm below the power-up tool point (nose -25 mm, tool 125 mm).
constexpr const char* kStock = "name = \"stock-1mm\"\n[stock]\nenabled = true\ntop_mm = -151.0\n";

TEST(PathStockCutCli, ACutWithTheSpindleOnIsExitZeroWithNoCrash) {
  const std::string scenario = temp_file("stock.toml", kStock);
  const std::string program = temp_file("cut.ngc", "G21 G91\nS6000 M3\nG1 Z-2 F300\nG1 X10 F1200\nG0 Z2\nM5\nM2\n");
  const CliRun r = run_tnv_hil("path " + program + " --scenario " + scenario + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["crashes"].get<int>(), 0);
  EXPECT_EQ(j["feed_before_at_speed"].get<int>(), 0);
  EXPECT_GE(j["feed_onsets"].get<int>(), 1);
  EXPECT_GT(j["tool_force_max_n"].get<double>(), 100.0);
  const CliRun text = run_tnv_hil("path " + program + " --scenario " + scenario);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("crashes 0  feed moves before the spindle was at speed 0"), std::string::npos) << text.out;
  std::filesystem::remove(scenario);
  std::filesystem::remove(program);
}

TEST(PathStockCutCli, FeedingIntoTheStockWithTheSpindleOffIsACrashAndExitOne) {
  const std::string scenario = temp_file("stock2.toml", kStock);
  const std::string program = temp_file("crash.ngc", "G21 G91\nG1 Z-2 F300\nG1 X5 F600\nG0 Z2\nM2\n");
  const CliRun r = run_tnv_hil("path " + program + " --scenario " + scenario + " --json");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_GE(j["crashes"].get<int>(), 1);
  EXPECT_NE(j["error"].get<std::string>().find("crash"), std::string::npos) << j["error"];
  EXPECT_NE(r.err.find("crash"), std::string::npos) << r.err;
  std::filesystem::remove(scenario);
  std::filesystem::remove(program);
}

}  // namespace
}  // namespace tnv::test
