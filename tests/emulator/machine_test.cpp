// The whole emulated machine through its register door.
#include "emulator/machine.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "emulator/axis_plant.hpp"
#include "emulator/cutting_disturbance.hpp"
#include "emulator/force_adc.hpp"
#include "emulator/scenario_file.hpp"
#include "hal/io_board_registers.hpp"
#include "tests/emulator/machine_register_read.hpp"

namespace tnv::emu {
namespace {

namespace regs = hal::regs;
using hal::Axis;

using test_support::read;

void servo_on(Machine& m, std::uint32_t dac_x = 2048, std::uint32_t dac_y = 2048) {
  ASSERT_TRUE(m.write_register(regs::kDacX, dac_x));
  ASSERT_TRUE(m.write_register(regs::kDacY, dac_y));
  ASSERT_TRUE(m.write_register(regs::kOutputs, regs::kOutputEnableX | regs::kOutputEnableY));
}

TEST(Machine, StartsAtRestStuckAtTheCircleStart) {
  Machine m(Scenario{});
  EXPECT_EQ(m.truth(Axis::x).position_mm, 6.0);
  EXPECT_EQ(m.truth(Axis::y).position_mm, 0.0);
  EXPECT_TRUE(m.truth(Axis::x).stuck);
  EXPECT_EQ(read(m, regs::kEncoderX), 14'400u) << "6 mm before the first tick too";
  m.advance_to_next_tick();
  EXPECT_EQ(m.elapsed_clocks(), 10'000u);
  EXPECT_DOUBLE_EQ(m.time_s(), 1e-3);
  EXPECT_EQ(read(m, regs::kTickSequence), 0u);
  EXPECT_EQ(read(m, regs::kEncoderX), 14'400u);
  EXPECT_EQ(read(m, regs::kEncoderY), 0u);
  EXPECT_EQ(m.truth(Axis::x).position_mm, 6.0) << "no command, no motion";
}

TEST(Machine, AdvanceClocksRoundsUpToWholeSubsteps) {
  Machine m(Scenario{});
  m.advance_clocks(1);
  EXPECT_EQ(m.elapsed_clocks(), 100u);
  m.advance_clocks(250);
  EXPECT_EQ(m.elapsed_clocks(), 400u);
}

TEST(Machine, CommandedSpeedDrivesTheTable) {
  Scenario s;
  s.plant[0].coulomb_mm_s = s.plant[0].stiction_mm_s = 0.0;  // friction off on X
  Machine m(s);
  servo_on(m, 2048 + 123, 2048);
  m.advance_to_next_tick();
  const double u_mm_s = 123 * 1000.0 * 10.0 / 60.0 / 2048.0;
  EXPECT_DOUBLE_EQ(m.truth(Axis::x).command_mm_s, u_mm_s);
  const double a22 = std::exp(-1e-3 / s.plant[0].tau_s);
  EXPECT_NEAR(m.truth(Axis::x).speed_mm_s, u_mm_s * (1.0 - a22), 1e-12) << "B2 u after one tick, mm/s";
  EXPECT_NEAR(m.truth(Axis::x).position_mm - 6.0, u_mm_s * (1e-3 - s.plant[0].tau_s * (1.0 - a22)), 1e-12);
  EXPECT_TRUE(m.truth(Axis::y).stuck) << "Y got mid-scale";
  const auto count = static_cast<std::int64_t>(read(m, regs::kEncoderX));
  EXPECT_EQ(count, std::llround(m.truth(Axis::x).position_mm / (10.0 / 24000.0)));
}

TEST(Machine, WatchdogTripStopsTheTable) {
  Scenario s;
  s.plant[0].coulomb_mm_s = s.plant[0].stiction_mm_s = 0.0;
  Machine m(s);
  servo_on(m, 3000);
  ASSERT_TRUE(m.write_register(regs::kWatchdogKick, regs::kWatchdogKickKey));
  for (int i = 0; i < 4; ++i) m.advance_to_next_tick();
  EXPECT_EQ(m.truth(Axis::x).command_mm_s, 0.0) << "watchdog tripped after 3 ms without a kick";
  for (int i = 0; i < 200; ++i) m.advance_to_next_tick();
  EXPECT_NEAR(m.truth(Axis::x).speed_mm_s, 0.0, 1e-9) << "table speed long after the trip, mm/s";
  EXPECT_NE(read(m, regs::kInputs) & regs::kInputWatchdogTripped, 0u);
}

TEST(Machine, ForceAdcReadsCuttingMagnitude) {
  Scenario s = *builtin_scenario("cut-900");
  s.force_sensor.volts_per_mm_s = 5.0;
  Machine m(s);
  servo_on(m, 2048 + 48, 2048);  // cutting follows the table: it has to move
  for (int i = 0; i < 300; ++i) m.advance_to_next_tick();
  const double magnitude = std::hypot(m.truth(Axis::x).cutting_mm_s, m.truth(Axis::y).cutting_mm_s);
  EXPECT_GT(magnitude, 0.0);
  EXPECT_EQ(read(m, regs::kAdcForce), force_adc_code(magnitude, 5.0));
  EXPECT_EQ(force_adc_code(1.0, 5.0), 2048u) << "5 V of 10 V";
  EXPECT_EQ(force_adc_code(3.0, 5.0), 4095u) << "clamped at full scale";
  EXPECT_EQ(force_adc_code(0.0, 5.0), 0u);
}

TEST(Machine, ToolPointIsTheTableWithoutAStructuralMode) {
  Scenario s;
  s.plant[0].coulomb_mm_s = s.plant[0].stiction_mm_s = 0.0;
  Machine m(s);
  servo_on(m, 2600);
  for (int i = 0; i < 20; ++i) m.advance_to_next_tick();
  EXPECT_EQ(m.truth(Axis::x).tool_position_mm, m.truth(Axis::x).position_mm);
}

TEST(Machine, StructuralModeLagsTheToolBehindAnAcceleratingTable) {
  Scenario s = *builtin_scenario("flex-30");
  s.plant[0].coulomb_mm_s = s.plant[0].stiction_mm_s = 0.0;
  Machine m(s);
  servo_on(m, 2600);
  m.advance_to_next_tick();
  const AxisTruth x = m.truth(Axis::x);
  EXPECT_LT(x.tool_position_mm, x.position_mm) << "tool lags while the table accelerates forward";
  EXPECT_EQ(m.truth(Axis::y).tool_position_mm, m.truth(Axis::y).position_mm) << "flex-30 has no Y mode";
}

TEST(Machine, WatchdogTripsAtTheExactSubstepBoundary) {
  Scenario s;
  s.plant[0].coulomb_mm_s = s.plant[0].stiction_mm_s = 0.0;
  Machine m(s);
  servo_on(m, 3000);
  ASSERT_TRUE(m.write_register(regs::kWatchdogKick, regs::kWatchdogKickKey));
  m.advance_clocks(30'100);  // the trip happens at the end of this stretch
  EXPECT_GT(m.truth(Axis::x).command_mm_s, 0.0) << "the sub-step ending at 30,100 clocks started before the trip";
  m.advance_clocks(100);
  EXPECT_EQ(m.truth(Axis::x).command_mm_s, 0.0) << "first sub-step after the trip";
  EXPECT_EQ(read(m, regs::kInputs) & regs::kInputWatchdogTripped, 0u) << "not latched before the 40,000 tick";
  m.advance_to_next_tick();
  EXPECT_EQ(m.elapsed_clocks(), 40'000u);
  EXPECT_NE(read(m, regs::kInputs) & regs::kInputWatchdogTripped, 0u);
}

TEST(Machine, ShortTickDividerStillTicksEveryDivider) {
  Machine m(Scenario{});
  ASSERT_TRUE(m.write_register(regs::kTickDivider, 150));
  m.advance_to_next_tick();
  EXPECT_EQ(m.elapsed_clocks(), 200u);
  m.advance_to_next_tick();
  EXPECT_EQ(m.elapsed_clocks(), 300u);
  EXPECT_EQ(read(m, regs::kTickSequence), 1u);
}

// The machine's block stepping must be the reference plant driven by the
// DAC command and the cutting model, nothing more.
TEST(Machine, TableFollowsThePlantDrivenByCommandAndCutting) {
  const Scenario s = *builtin_scenario("cut-1200");
  Machine m(s);
  servo_on(m, 2048 + 40, 2048 - 30);
  AxisPlant x(s.plant[0]), y(s.plant[1]);
  x.set_state(6.0, 0.0, true);
  y.set_state(0.0, 0.0, true);
  const CuttingDisturbance cutting(s.cutting, s.circle.feed_mm_s);
  const double lsb_mm_s = 1000.0 * 10.0 / 60.0 / 2048.0;
  std::uint64_t substep = 0;
  for (int tick = 0; tick < 800; ++tick) {
    m.advance_to_next_tick();
    for (int i = 0; i < 100; ++i, ++substep) {
      // The force of each sub-step from the table's velocity at its start.
      const CuttingVector d = cutting.at_substep(substep, x.speed_mm_s(), y.speed_mm_s());
      x.step(40 * lsb_mm_s, d.x_mm_s);
      y.step(-30 * lsb_mm_s, d.y_mm_s);
    }
    // Rounding only: the machine turns the tooth phase by precomputed
    // rotations where this reference takes a sin per sub-step.
    ASSERT_NEAR(m.truth(Axis::x).position_mm, x.position_mm(), 1e-10) << "X at tick " << tick;
    ASSERT_NEAR(m.truth(Axis::y).position_mm, y.position_mm(), 1e-10) << "Y at tick " << tick;
    ASSERT_NEAR(m.truth(Axis::x).speed_mm_s, x.speed_mm_s(), 1e-12) << "X at tick " << tick;
    ASSERT_EQ(m.truth(Axis::x).stuck, x.stuck()) << "tick " << tick;
  }
  EXPECT_NE(m.truth(Axis::x).cutting_mm_s, 0.0);
}

TEST(Machine, BenchInputsReachTheSnapshot) {
  Machine m(Scenario{});
  m.set_estop(true);
  m.set_servo_alarm(Axis::y, true);
  m.set_limit(Axis::x, false, true);
  m.advance_to_next_tick();
  EXPECT_EQ(read(m, regs::kInputs), regs::kInputEstop | regs::kInputAlarmY | regs::kInputLimitXNeg);
}

// A refused word refuses the whole block: a bad request (e.g. from a client
// of tnv-board-emu's socket) changes no register, not only those after it.
TEST(Machine, ABlockWriteIsAllOrNothing) {
  Machine m(Scenario{});
  servo_on(m, 2100, 2000);
  // The tick's output block: OUTPUTS, the kick, the spindle's DAC, then the axes' DACs.
  const auto outputs_block = [](std::uint32_t outputs, std::uint32_t dac_x, std::uint32_t dac_y) {
    std::array<std::uint32_t, regs::kOutputWords> out{};
    out.fill(2048u);
    out[regs::kOutputs - regs::kOutputFirst] = outputs;
    out[regs::kWatchdogKick - regs::kOutputFirst] = 0;
    out[regs::kDacX - regs::kOutputFirst] = dac_x;
    out[regs::kDacY - regs::kOutputFirst] = dac_y;
    return out;
  };
  // The last DAC word is above 4095: the OUTPUTS and DAC words before it must not land either.
  EXPECT_FALSE(m.write_registers(regs::kOutputFirst, outputs_block(regs::kOutputEnableX, 2500, 5000)));
  EXPECT_FALSE(m.write_registers(regs::kOutputFirst, outputs_block(0x8000'0000u, 2500, 1500)))
      << "OUTPUTS: a bit the board lacks";
  const std::array<std::uint32_t, 2> past_the_map{1u, 0u};  // CONTROL, then the word after the last register
  EXPECT_FALSE(m.write_registers(regs::kLastRegister, past_the_map));
  const std::array<std::uint32_t, 2> wrapping{1u, 2u};
  EXPECT_FALSE(m.write_registers(0xFFFF, wrapping));
  m.advance_to_next_tick();
  EXPECT_EQ(m.board_outputs().dac_register[0], 2100u) << "DAC_X of the refused blocks did not land";
  EXPECT_EQ(m.board_outputs().dac_register[1], 2000u);
  EXPECT_TRUE(m.board_outputs().enabled[0]);
  EXPECT_TRUE(m.board_outputs().enabled[1]) << "OUTPUTS before the refused DAC word did not land";

  ASSERT_TRUE(m.write_registers(regs::kOutputFirst, outputs_block(regs::kOutputEnableX, 2500, 1500)));
  m.advance_to_next_tick();
  EXPECT_EQ(m.board_outputs().dac_register[0], 2500u);
  EXPECT_EQ(m.board_outputs().dac_register[1], 1500u);
  EXPECT_FALSE(m.board_outputs().enabled[1]);
}

}  // namespace
}  // namespace tnv::emu
