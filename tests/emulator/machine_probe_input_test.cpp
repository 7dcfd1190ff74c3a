// The touch probe on the board's INPUTS bit 2 (docs/machine.md "Touch
// probe"): set at each tick latch while the probe tip at the tool point
// touches [stock], never without a stock.
#include <gtest/gtest.h>

#include <cstdint>

#include "emulator/machine.hpp"
#include "hal/io_board_registers.hpp"
#include "tests/emulator/machine_register_read.hpp"

namespace tnv::emu {
namespace {

using test_support::read;

// The head stands at [plant.z] start_mm; with the default 125 mm tool its
// tool point is start_mm - 125. The table powers up at (circle radius, 0) = (6, 0).
Scenario head_at(double nose_z_mm, bool stock = true) {
  Scenario s;
  s.z_axis.start_mm = nose_z_mm;
  s.stock.enabled = stock;
  s.stock.top_mm = -150.0;
  return s;
}

bool probe_bit(const Scenario& s) {
  Machine m(s);
  m.advance_to_next_tick();
  return (read(m, hal::regs::kInputs) & hal::regs::kInputProbe) != 0;
}

TEST(MachineProbeInput, TheTopFaceTripsItAtTheToolPoint) {
  EXPECT_TRUE(probe_bit(head_at(-25.0))) << "tool point -150 mm on the top face at -150 mm";
  EXPECT_TRUE(probe_bit(head_at(-30.0))) << "tool point 5 mm into the stock";
  EXPECT_FALSE(probe_bit(head_at(-24.99))) << "tool point 10 um above the top face";
}

TEST(MachineProbeInput, AScenarioWithoutAStockNeverTrips) {
  EXPECT_FALSE(probe_bit(head_at(-100.0, false))) << "tool point 75 mm below where a stock's top would be";
}

TEST(MachineProbeInput, ASideFaceTripsItWithinTheTipRadius) {
  // The table at X = 6 mm, the stock's side at X = 5 mm: 1 mm in XY from the tool point.
  Scenario s = head_at(-30.0);
  s.stock.x_max_mm = 5.0;
  EXPECT_FALSE(probe_bit(s)) << "a point probe 1 mm from the side";
  s.probe.tip_radius_mm = 0.99;
  EXPECT_FALSE(probe_bit(s)) << "a 0.99 mm ball 1 mm from the side";
  s.probe.tip_radius_mm = 1.0;
  EXPECT_TRUE(probe_bit(s)) << "a 1 mm ball 1 mm from the side";
}

TEST(MachineProbeInput, TheBitFollowsTheToolAsItMoves) {
  // Enabled Z with a constant command drives the head down: the bit rises
  // at the first latch with the tool point at the top face or below.
  Scenario s = head_at(-24.5);
  Machine m(s);
  m.advance_to_next_tick();
  ASSERT_EQ(read(m, hal::regs::kInputs) & hal::regs::kInputProbe, 0u);
  const hal::regs::AxisRegisters& z = hal::regs::axis_registers(hal::Axis::z);
  const std::uint32_t mid = m.dac_mid_code();
  ASSERT_TRUE(m.write_register(hal::regs::kOutputs, z.output_enable));
  ASSERT_TRUE(m.write_register(z.dac, mid - 200));  // downward
  bool seen = false;
  for (int tick = 0; tick < 5000 && !seen; ++tick) {
    m.advance_to_next_tick();
    seen = (read(m, hal::regs::kInputs) & hal::regs::kInputProbe) != 0;
    if (seen) {
      const double tool_z_mm = m.truth(hal::Axis::z).position_mm - s.tool.length_mm;
      EXPECT_LE(tool_z_mm, s.stock.top_mm) << "the bit is set only with the tool point on or in the stock";
    } else {
      // (the watchdog must be kicked for the drive to stay enabled)
      ASSERT_TRUE(m.write_register(hal::regs::kWatchdogKick, hal::regs::kWatchdogKickKey));
    }
  }
  EXPECT_TRUE(seen) << "the head never reached the stock";
}

}  // namespace
}  // namespace tnv::emu
