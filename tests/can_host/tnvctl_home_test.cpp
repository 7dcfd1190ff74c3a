// `tnvctl home` on the emulated node: homes both axes (x then y) on a table
// with home switches and reports them homed; one axis alone; a bad --axis
// is refused before anything is sent; without a switch the search runs out
// of its travel and the command fails naming the fault.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/can_host/tnvctl_runner.hpp"

namespace tnv {
namespace {

// x stands at 6 mm and y at 0 at power-up: switches below them, index marks past the releases.
constexpr const char* kSwitches = R"(name = "home-switches"
[board]
home_switch_x = true
home_switch_y = true
home_x_mm = 2.0
home_y_mm = -3.0
index_x_deg = 108.0
index_y_deg = 0.0
)";

// --json prints one JSON document for a single command.
nlohmann::json result_of(const std::string& out) {
  nlohmann::json j = nlohmann::json::parse(out, nullptr, false);
  EXPECT_FALSE(j.is_discarded()) << out;
  return j.is_discarded() ? nlohmann::json::object() : j;
}

TEST(TnvctlHome, HomesBothAxesOnTheEmulatedTable) {
  const auto state = test::state_dir("home_all");
  const auto scenario = test::write_file(state / "home.toml", kSwitches);
  const test::ToolRun r = test::tnvctl(state, "--emu --json --emu-scenario " + scenario.string() + " home");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json j = result_of(r.out);
  ASSERT_EQ(j["command"], "home") << r.out;
  EXPECT_EQ(j["homed"]["x"], true) << j.dump();
  EXPECT_EQ(j["homed"]["y"], true) << j.dump();
  EXPECT_EQ(j["status"]["state"], "holding") << j.dump();
  std::filesystem::remove_all(state);
}

TEST(TnvctlHome, OneAxisAloneAndABadAxisRefused) {
  const auto state = test::state_dir("home_y");
  const auto scenario = test::write_file(state / "home.toml", kSwitches);
  const test::ToolRun y = test::tnvctl(state, "--emu --json --emu-scenario " + scenario.string() + " home --axis y");
  ASSERT_EQ(y.exit_code, 0) << y.err << y.out;
  const nlohmann::json j = result_of(y.out);
  EXPECT_EQ(j["homed"]["x"], false) << j.dump();
  EXPECT_EQ(j["homed"]["y"], true) << j.dump();
  const test::ToolRun bad = test::tnvctl(state, "--emu home --axis w");
  EXPECT_EQ(bad.exit_code, 2) << bad.out << bad.err;
  std::filesystem::remove_all(state);
}

TEST(TnvctlHome, NoSwitchFailsNamingTheFault) {
  const auto state = test::state_dir("home_no_switch");
  // The default scenario has no home switch: the search runs x.homing.search_max_mm (400 mm) and faults.
  const test::ToolRun r = test::tnvctl(state, "--emu home --axis x");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE((r.out + r.err).find("homing_failed"), std::string::npos) << r.out << r.err;
  std::filesystem::remove_all(state);
}

}  // namespace
}  // namespace tnv
