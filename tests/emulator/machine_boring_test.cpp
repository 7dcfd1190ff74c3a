// The boring bar in emu::Machine ([boring] with [stock]): the head driven
// down through its DAC register with the spindle turning bores the hole;
// the gauge depths see the infeed per revolution of the head's real speed
// and the spindle's real speed, and the deflection (S4 eq. 2) grows with
// the overhang and with the infeed. Off by default.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "emulator/boring_pass.hpp"
#include "emulator/cutting_at_tool.hpp"
#include "emulator/machine.hpp"
#include "emulator/scenario_file.hpp"
#include "emulator/scenario_validation.hpp"
#include "hal/io_board_registers.hpp"

namespace tnv::emu {
namespace {

namespace regs = hal::regs;

constexpr std::uint32_t kCode3000Rpm = 2048 + 512;  // 2.5 V: 3000 rpm

Scenario boring_machine() {
  Scenario s;
  s.stock.enabled = true;
  s.boring.enabled = true;
  s.boring.sigma_d_um = 0.0;  // the true bore, read by an exact gauge
  s.z_axis.start_mm = -20.0;  // tool point 5 mm above the stock top
  return s;
}

struct Pass {
  std::array<GaugeDepthReading, BoringPass::kGaugeDepths> gauge{};
  double min_error_mm = 0.0, max_error_mm = 0.0;
  double speed_at_bottom_mm_s = 0.0;
  std::uint64_t crashes = 0;
};

// The spindle to 3000 rpm, then Z enabled at a constant downward command
// until the tool point is 272 mm below the stock top.
Pass bore(const Scenario& s, std::uint32_t z_codes_down, int part = 1) {
  Machine m(s);
  const regs::AxisRegisters& z = regs::axis_registers(hal::Axis::z);
  const auto kick = [&m] { EXPECT_TRUE(m.write_register(regs::kWatchdogKick, regs::kWatchdogKickKey)); };
  EXPECT_TRUE(m.write_register(regs::kDacSpindle, kCode3000Rpm));
  EXPECT_TRUE(m.write_register(regs::kOutputs, regs::kOutputSpindleEnable));
  for (int tick = 0; tick < 1500; ++tick) {  // 0.5 s ramp and the drive's lag
    m.advance_to_next_tick();
    kick();
  }
  BoringPass& bar = *m.boring_pass();
  bar.begin_part(part);
  EXPECT_TRUE(m.write_register(z.dac, m.dac_mid_code() - z_codes_down));
  EXPECT_TRUE(m.write_register(regs::kOutputs, regs::kOutputSpindleEnable | z.output_enable));
  const double bottom_mm = s.stock.top_mm - 272.0 + s.tool.length_mm;
  Pass out;
  for (int tick = 0; tick < 200'000 && m.truth(hal::Axis::z).position_mm > bottom_mm; ++tick) {
    m.advance_to_next_tick();
    kick();
    out.speed_at_bottom_mm_s = m.truth(hal::Axis::z).speed_mm_s;
  }
  EXPECT_LE(m.truth(hal::Axis::z).position_mm, bottom_mm) << "the head never reached the bottom";
  out.min_error_mm = bar.min_radius_error_mm();
  out.max_error_mm = bar.max_radius_error_mm();
  out.gauge = bar.read_gauge();
  out.crashes = m.cutting_at_tool()->crashes().count();
  return out;
}

TEST(MachineBoring, OffByDefaultAndOnlyWithAStock) {
  EXPECT_EQ(Machine{Scenario{}}.boring_pass(), nullptr);
  Scenario s;
  s.stock.enabled = true;
  EXPECT_EQ(Machine{s}.boring_pass(), nullptr) << "a stock alone is milled, not bored";
  s.stock.enabled = false;
  s.boring.enabled = true;
  EXPECT_NE(validate_scenario(s).find("boring.enabled"), std::string::npos) << validate_scenario(s);
  EXPECT_NE(Machine{boring_machine()}.boring_pass(), nullptr);
  // The key, from a scenario file; refused without the stock, naming the key.
  const ScenarioResult on = parse_scenario_text("[stock]\nenabled = true\n[boring]\nenabled = true\n", "on.toml");
  ASSERT_TRUE(on.scenario) << on.error;
  EXPECT_TRUE(on.scenario->boring.enabled);
  const ScenarioResult off = parse_scenario_text("[boring]\nenabled = true\n", "off.toml");
  EXPECT_FALSE(off.scenario);
  EXPECT_NE(off.error.find("boring.enabled"), std::string::npos) << off.error;
}

TEST(MachineBoring, ThePassSetsTheBoreFromTheHeadsAndTheSpindlesRealSpeeds) {
  const Scenario s = boring_machine();
  const Pass p = bore(s, 300);
  ASSERT_TRUE(p.gauge[0].cut);
  ASSERT_TRUE(p.gauge[1].cut);
  EXPECT_EQ(p.crashes, 0u) << "the spindle was at speed";
  // Overhangs within one sub-step's travel of L0 and L0 + 270 mm.
  const double substep_travel_mm = std::fabs(p.speed_at_bottom_mm_s) * 1e-5;
  EXPECT_NEAR(p.gauge[0].overhang_mm, 40.0, substep_travel_mm + 1e-9);
  EXPECT_NEAR(p.gauge[1].overhang_mm, 310.0, substep_travel_mm + 1e-9);
  // A constant command: the head at a steady speed, the same infeed at both
  // depths, the head's speed over the spindle's 50 rev/s.
  const double infeed = -p.speed_at_bottom_mm_s / 50.0;
  EXPECT_GT(infeed, 0.01);
  EXPECT_NEAR(p.gauge[1].infeed_mm_rev, infeed, 0.01 * infeed);
  EXPECT_NEAR(p.gauge[0].infeed_mm_rev, p.gauge[1].infeed_mm_rev, 0.01 * infeed);
  // Deeper is more overhang, more deflection: the bottom's error is larger, and the pass's largest.
  const BoringProcess truth(boring_process_config(s));
  EXPECT_GT(p.gauge[1].radius_error_mm, p.gauge[0].radius_error_mm);
  EXPECT_NEAR(p.gauge[1].radius_error_mm,
              truth.deflection_mm(1, p.gauge[1].infeed_mm_rev, p.gauge[1].overhang_mm) - 0.1165, 1e-12);
  EXPECT_NEAR(p.max_error_mm, truth.deflection_mm(1, p.gauge[1].infeed_mm_rev, 312.0) - 0.1165, 1e-3)
      << "the deepest point of the pass (2 mm below the bottom gauge depth) bends most";
  EXPECT_LE(p.min_error_mm, p.gauge[0].radius_error_mm + 1e-12);
}

TEST(MachineBoring, AFasterFeedBoresAMoreDeflectedHoleAndTheLaterSetsTakeOver) {
  const Scenario s = boring_machine();
  const Pass slow = bore(s, 150);
  const Pass fast = bore(s, 600);
  for (std::size_t i = 0; i < BoringPass::kGaugeDepths; ++i) {
    ASSERT_TRUE(slow.gauge[i].cut && fast.gauge[i].cut);
    EXPECT_GT(fast.gauge[i].infeed_mm_rev, 2.0 * slow.gauge[i].infeed_mm_rev);
    EXPECT_GT(fast.gauge[i].radius_error_mm, slow.gauge[i].radius_error_mm) << "depth " << i;
    // S4 eq. 2: the ratio of deflections is the infeed ratio to the power alpha (0.5025, Table 1).
    const double d_fast = fast.gauge[i].radius_error_mm + 0.1165;
    const double d_slow = slow.gauge[i].radius_error_mm + 0.1165;
    EXPECT_NEAR(std::log(d_fast / d_slow) / std::log(fast.gauge[i].infeed_mm_rev / slow.gauge[i].infeed_mm_rev),
                0.5025, 0.01);
  }
  // Part 11 is cut with S4 section 5's second set (alpha 0.7, beta 0.4, C 0.15 mm).
  const Pass later = bore(s, 150, 11);
  const double d = later.gauge[1].radius_error_mm + 0.1165;
  EXPECT_NEAR(d, 0.15 * std::pow(later.gauge[1].infeed_mm_rev, 0.7) * std::pow(later.gauge[1].overhang_mm, 0.4),
              1e-12);
}

}  // namespace
}  // namespace tnv::emu
