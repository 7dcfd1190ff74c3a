// The spindle in the emulated machine at register level: DAC_SPINDLE and the
// OUTPUTS spindle bits drive its drive; SPINDLE_ENCODER follows it. (The
// driver's view, speeds and the index: tests/drivers/fpga_spindle_test.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "emulator/machine.hpp"
#include "hal/io_board_registers.hpp"
#include "tests/emulator/machine_register_read.hpp"

namespace tnv::emu {
namespace {

namespace regs = hal::regs;
using test_support::read;

constexpr std::uint32_t kCode3000Rpm = 2048 + 512;  // 2.5 V: 3000 rpm

TEST(MachineSpindle, AnIdleSpindleStaysAtRestAndItsCountStill) {
  Machine m{Scenario{}};
  for (int i = 0; i < 50; ++i) m.advance_to_next_tick();
  EXPECT_TRUE(m.spindle_truth().at_rest);
  EXPECT_EQ(m.spindle_truth().revolutions, 0.0);
  EXPECT_EQ(read(m, regs::kSpindleEncoder), 0u);
  EXPECT_EQ(read(m, regs::kSpindleIndex), 0u) << "no edge yet";
  // A speed written without the enable does not turn it either.
  ASSERT_TRUE(m.write_register(regs::kDacSpindle, kCode3000Rpm));
  for (int i = 0; i < 50; ++i) m.advance_to_next_tick();
  EXPECT_TRUE(m.spindle_truth().at_rest);
  EXPECT_FALSE(m.board_outputs().safe(m.dac_mid_code())) << "a spindle DAC off mid-scale is not safe";
}

TEST(MachineSpindle, EnabledItTurnsAndTheEncoderRegisterFollowsItsRevolutions) {
  Machine m{Scenario{}};
  ASSERT_TRUE(m.write_register(regs::kDacSpindle, kCode3000Rpm));
  ASSERT_TRUE(m.write_register(regs::kOutputs, regs::kOutputSpindleEnable));
  for (int i = 0; i < 100; ++i) m.advance_to_next_tick();
  const SpindleTruth t = m.spindle_truth();
  EXPECT_EQ(t.command_rpm, 3000.0);
  EXPECT_NEAR(t.speed_rpm, 600.0, 1e-6) << "0.1 s at the drive's 6000 rpm/s";
  EXPECT_NEAR(t.revolutions, 0.5 * 6000.0 * 0.1 * 0.1 / 60.0, 1e-9);
  EXPECT_EQ(read(m, regs::kSpindleEncoder), static_cast<std::uint32_t>(std::llround(t.revolutions * 4096.0)));
}

TEST(MachineSpindle, WithIoLatencyTheSpindleWritesLandWithTheAxes) {
  Scenario s;
  s.io = IoParams{.read_latency_us = 100.0, .write_latency_us = 50.0};
  Machine m(s);
  m.advance_to_next_tick();
  ASSERT_TRUE(m.write_register(regs::kDacSpindle, kCode3000Rpm));
  ASSERT_TRUE(m.write_register(regs::kOutputs, regs::kOutputSpindleEnable));
  EXPECT_EQ(read(m, regs::kDacSpindle), kCode3000Rpm) << "the register has it at once";
  m.advance_clocks(1'000);  // 100 us: still on the link
  EXPECT_FALSE(m.board_outputs().spindle_enabled);
  EXPECT_TRUE(m.spindle_truth().at_rest);
  m.advance_clocks(1'000);  // 200 us: landed at 150 us
  EXPECT_TRUE(m.board_outputs().spindle_enabled);
  EXPECT_EQ(m.spindle_truth().command_rpm, 3000.0);
  EXPECT_GT(m.spindle_truth().speed_rpm, 0.0);
}

}  // namespace
}  // namespace tnv::emu
