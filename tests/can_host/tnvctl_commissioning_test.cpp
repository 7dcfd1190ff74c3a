// tnvctl and commissioning mode: a safety parameter set outside it exits 1
// naming commissioning; `commissioning enter` makes it writable (within
// its range), `leave` and enable lock it again. docs/safety.md "Commissioning".
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/can_host/tnvctl_runner.hpp"

namespace tnv {
namespace {

using test::ToolRun;

bool mentions(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string commission_script(const std::filesystem::path& script) {
  std::string args = "--emu script ";
  return args.append(script.string());
}

TEST(TnvctlCommissioning, ASafetyParameterOutsideTheModeExits1NamingCommissioning) {
  const auto state = test::state_dir("commission-refused");
  // The abuse, out of the tightened range too: the refusal that names commissioning comes first.
  ToolRun r = test::tnvctl(state, "--emu params set x.limits.following_floor_mm=100");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(mentions(r.err, "x.limits.following_floor_mm is a safety parameter: enter commissioning mode first "
                         "(tnvctl commissioning enter, servo disabled)"))
      << r.err;
  // In range, with another parameter in the same set: refused whole.
  r = test::tnvctl(state, "--emu --json params set x.pid.kp=300 supervisor.max_missed_ticks=5");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(mentions(j["error"].get<std::string>(), "supervisor.max_missed_ticks is a safety parameter")) << j.dump();
  r = test::tnvctl(state, "--emu --json params get x.pid.kp supervisor.max_missed_ticks");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json after = nlohmann::json::parse(r.out);
  EXPECT_NE(after["params"][0]["value"], 300.0) << "nothing applied";
  EXPECT_EQ(after["params"][1]["value"], 2) << "the default";
  EXPECT_EQ(after["params"][1]["safety"], true);
  std::filesystem::remove_all(state);
}

TEST(TnvctlCommissioning, InTheModeTheSafetyParametersChangeWithinTheirRanges) {
  const auto state = test::state_dir("commission-ok");
  const auto script = test::write_file(state / "commission.tnvctl",
                                       "commissioning enter\nstatus\n"
                                       "params set x.limits.following_floor_mm=0.08 supervisor.max_missed_ticks=3\n"
                                       "commissioning leave\n");
  ToolRun r = test::tnvctl(state, commission_script(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(mentions(r.out, "flags commissioning")) << "the heartbeat shows it: " << r.out;
  EXPECT_TRUE(mentions(r.out, "x.limits.following_floor_mm = 0.08 mm (was 0.05)")) << r.out;
  // Out of the tightened range even in the mode: refused by the node with the range.
  const auto abuse = test::write_file(state / "abuse.tnvctl",
                                      "commissioning enter\nparams set x.limits.following_lag_s=10\n");
  r = test::tnvctl(state, commission_script(abuse));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(mentions(r.err, "out_of_range (x.limits.following_lag_s range 0 .. 0.25")) << r.err;
  // Enable leaves the mode.
  const auto enable = test::write_file(state / "enable.tnvctl",
                                       "commissioning enter\nenable\ndisable\nparams set x.limits.following_floor_mm=0.1\n");
  r = test::tnvctl(state, commission_script(enable));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(mentions(r.err, "enable.tnvctl:4")) << r.err;
  EXPECT_TRUE(mentions(r.err, "enter commissioning mode first")) << r.err;
  std::filesystem::remove_all(state);
}

TEST(TnvctlCommissioning, EnteringWhileTheServoIsOnIsRefusedWithTheReason) {
  const auto state = test::state_dir("commission-busy");
  const auto script = test::write_file(state / "busy.tnvctl", "enable\ncommissioning enter\n");
  const ToolRun r = test::tnvctl(state, commission_script(script));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(mentions(r.err, "busy")) << r.err;
  EXPECT_TRUE(mentions(r.err, "servo disabled (tnvctl disable)")) << r.err;
  std::filesystem::remove_all(state);
}

}  // namespace
}  // namespace tnv
