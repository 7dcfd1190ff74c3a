// `tnvctl spindle` on the emulated node: start, speed and stop answered by
// the node; a bad speed refused before anything is sent (exit 2); a speed
// change of a spindle that is not turning refused by the node (exit 1,
// naming why); `tnvctl monitor` shows the turning spindle from TLM_SPINDLE.
#include <gtest/gtest.h>

#include <cstdio>

#include <nlohmann/json.hpp>

#include "tests/can_host/tnvctl_runner.hpp"

namespace tnv {
namespace {

TEST(TnvctlSpindle, StartSpeedAndStopAreAcceptedByTheNode) {
  const auto state = test::state_dir("spindle_script");
  const auto script = test::write_file(state / "spindle.txt",
                                       "spindle start --rpm 3000 --reverse\nspindle speed 2000\nspindle stop\n");
  const test::ToolRun r = test::tnvctl(state, "--emu script " + script.string());
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("spindle started: reverse at 3000 rpm"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("spindle speed: 2000 rpm"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("spindle stopping"), std::string::npos) << r.out;
  const test::ToolRun j = test::tnvctl(state, "--emu --json spindle start --rpm 1500");
  ASSERT_EQ(j.exit_code, 0) << j.err << j.out;
  const nlohmann::json doc = nlohmann::json::parse(j.out);
  EXPECT_EQ(doc["command"], "spindle") << j.out;
  EXPECT_EQ(doc["op"], "start") << j.out;
  EXPECT_EQ(doc["direction"], "forward") << j.out;
  EXPECT_EQ(doc["rpm"], 1500.0) << j.out;
  std::filesystem::remove_all(state);
}

TEST(TnvctlSpindle, ABadSpeedIsRefusedBeforeAnythingIsSentAndTheNodeRefusesASpeedWithoutAStart) {
  const auto state = test::state_dir("spindle_bad");
  const test::ToolRun zero = test::tnvctl(state, "--emu spindle start --rpm 0");
  EXPECT_EQ(zero.exit_code, 2) << zero.out << zero.err;
  const test::ToolRun fast = test::tnvctl(state, "--emu spindle speed 20000");
  EXPECT_EQ(fast.exit_code, 2) << fast.out << fast.err;
  const test::ToolRun idle = test::tnvctl(state, "--emu spindle speed 1000");
  EXPECT_EQ(idle.exit_code, 1) << idle.out << idle.err;
  EXPECT_NE(idle.err.find("not_ready"), std::string::npos) << idle.err;
  std::filesystem::remove_all(state);
}

TEST(TnvctlSpindle, MonitorShowsTheSpindleReachingSpeed) {
  const auto state = test::state_dir("spindle_monitor");
  const auto script = test::write_file(
      state / "spindle.txt", "params set tlm.spindle_ms=10\nspindle start --rpm 1000\nmonitor --duration-s 1 --rate-hz 5\n");
  const test::ToolRun r = test::tnvctl(state, "--emu script " + script.string());
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  // The last sample, a second after the start (a 0.2 s ramp at spindle.accel_rpm_s): at speed.
  const std::size_t last = r.out.rfind("spindle at_speed");
  ASSERT_NE(last, std::string::npos) << r.out;
  double measured_rpm = 0.0;
  ASSERT_EQ(std::sscanf(r.out.c_str() + last, "spindle at_speed %lf", &measured_rpm), 1) << r.out;
  EXPECT_NEAR(measured_rpm, 1000.0, 50.0) << r.out;
  std::filesystem::remove_all(state);
}

}  // namespace
}  // namespace tnv
