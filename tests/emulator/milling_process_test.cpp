// The S3 end-milling process as the paper simulates it (eqs. (27)-(28)) and
// the milling force on the emulated machine ([milling]).
#include <gtest/gtest.h>

#include <cmath>

#include "emulator/machine.hpp"
#include "emulator/milling_process.hpp"
#include "emulator/scenario_file.hpp"
#include "emulator/scenario_validation.hpp"
#include "hal/io_board_registers.hpp"

namespace tnv::emu {
namespace {

double dac_code_speed(double speed_mm_s, double lsb_mm_s) { return std::round(speed_mm_s / lsb_mm_s) * lsb_mm_s; }

TEST(MillingProcess, CoefficientsAreThePapersAtItsConstants) {
  const MillingCoefficients c = milling_coefficients(MillingProcessParams{});
  // The paper prints them to 4 decimals (below eq. (28)).
  EXPECT_NEAR(c.a11, -0.5488, 5e-5);
  EXPECT_NEAR(c.b11, 0.4512, 5e-5);
  EXPECT_NEAR(c.a21, -0.4724, 5e-5);
  EXPECT_NEAR(c.b21, 0.7915, 5e-5);
}

TEST(MillingProcess, SteadyStateIsFeedGainAndCuttingCoefficient) {
  // v = K_vs (u - f), f = C_fs delta v at rest of the dynamics.
  MillingProcess p(MillingProcessParams{});
  const double u = 2.0, depth = 0.6;
  for (int i = 0; i < 400; ++i) p.step(u, depth);
  EXPECT_NEAR(p.feed(), 1.0 * (u - p.force()), 1e-9);
  EXPECT_NEAR(p.force(), 1.5 * depth * p.feed(), 1e-9);
}

TEST(MillingProcess, OneStepIsEquations27And28) {
  MillingProcess p(MillingProcessParams{});
  p.step(1.0, 0.5);  // from rest: v(1) = b11 u(0), f(1) = 0
  EXPECT_NEAR(p.feed(), p.coefficients().b11, 1e-15);
  EXPECT_EQ(p.force(), 0.0);
  const double v1 = p.feed();
  p.step(0.0, 0.5);  // f(2) = b21 delta(1) v(1); v(2) = -a11 v(1) + b11 (0 - f(1))
  EXPECT_NEAR(p.force(), p.coefficients().b21 * 0.5 * v1, 1e-15);
  EXPECT_NEAR(p.feed(), -p.coefficients().a11 * v1, 1e-15);
}

TEST(MillingProcess, DepthProfileIsFig4) {
  const DepthProfile d{};  // 0.2 -> 1.0 over 15 s, back over 15 s
  EXPECT_DOUBLE_EQ(depth_profile_mm(d, 0.0), 0.2);
  EXPECT_NEAR(depth_profile_mm(d, 7.5), 0.6, 1e-12);
  EXPECT_NEAR(depth_profile_mm(d, 15.0), 1.0, 1e-12);
  EXPECT_NEAR(depth_profile_mm(d, 22.5), 0.6, 1e-12);
  EXPECT_NEAR(depth_profile_mm(d, 30.0), 0.2, 1e-12);
  EXPECT_NEAR(depth_profile_mm(d, 40.0), 0.2, 1e-12);
}

TEST(MillingProcess, InvalidParametersAreNamed) {
  MillingProcessParams p;
  p.force_time_constant_s = 0.0;
  EXPECT_NE(validate_milling_process(p).find("force_time_constant_s"), std::string::npos);
}

TEST(MachineMilling, ForceOnTheAdcFollowsFeedAndDepthAndSlowsTheFeed) {
  Scenario s;
  s.milling.enabled = true;
  s.milling.depth = {0.5, 0.5, 0.0, 0.0};  // constant 0.5 mm
  ASSERT_EQ(validate_scenario(s), "");
  Machine m(s);
  // X enabled at a constant 20 mm/s command: DAC code mid + 20 / LSB.
  const double lsb_mm_s = (1000.0 * 10.0 / 60.0) / 2048.0;
  m.write_register(hal::regs::kDacX, 2048u + static_cast<std::uint32_t>(std::lround(20.0 / lsb_mm_s)));
  m.write_register(hal::regs::kOutputs, hal::regs::kOutputEnableX);
  for (int i = 0; i < 2000; ++i) {  // 2 s = 10 force time constants
    m.write_register(hal::regs::kWatchdogKick, hal::regs::kWatchdogKickKey);
    m.advance_to_next_tick();
  }
  const double v = m.truth(hal::Axis::x).speed_mm_s;
  const double f = m.milling_force_n();
  EXPECT_NEAR(f, 15.0 * 0.5 * v, 0.01 * f) << "steady force K delta v";
  // The force slows the table: K u - friction - feed_load f.
  EXPECT_NEAR(v, dac_code_speed(20.0, lsb_mm_s) - 1.5 - 0.004 * f, 0.05);
  std::uint32_t code = 0;
  ASSERT_TRUE(m.read_register(hal::regs::kAdcForce, code));
  const double volts = f * s.force_sensor.volts_per_n;
  EXPECT_NEAR(static_cast<double>(code), volts / 10.0 * 4095.0, 1.0) << "ADC reads the milling force";
}

TEST(MachineMilling, OffByDefaultLeavesTheMachineAsItWas) {
  Scenario s;
  EXPECT_FALSE(s.milling.enabled);
  Machine m(s);
  for (int i = 0; i < 10; ++i) m.advance_to_next_tick();
  EXPECT_EQ(m.milling_force_n(), 0.0);
}

TEST(MachineMilling, ScenarioKeysParseAndBadValuesAreRefusedByName) {
  ScenarioResult ok = parse_scenario_text(
      "[milling]\nenabled = true\nforce_n_per_mm_mm_s = 20.0\nrise_s = 6\nfall_s = 6\n"
      "[force_sensor]\nvolts_per_n = 0.05\n",
      "mill.toml");
  ASSERT_TRUE(ok.scenario) << ok.error;
  EXPECT_TRUE(ok.scenario->milling.enabled);
  EXPECT_EQ(ok.scenario->milling.force_n_per_mm_mm_s, 20.0);
  EXPECT_EQ(ok.scenario->milling.depth.rise_s, 6.0);
  EXPECT_EQ(ok.scenario->force_sensor.volts_per_n, 0.05);
  ScenarioResult bad = parse_scenario_text("[milling]\ntime_constant_s = -1.0\n", "bad.toml");
  EXPECT_FALSE(bad.scenario);
  EXPECT_NE(bad.error.find("milling.time_constant_s"), std::string::npos) << bad.error;
  bad = parse_scenario_text("[milling]\ndepth_peak_mm = nan\n", "bad.toml");
  EXPECT_FALSE(bad.scenario);
  EXPECT_NE(bad.error.find("milling.depth_peak_mm"), std::string::npos) << bad.error;
}

}  // namespace
}  // namespace tnv::emu
