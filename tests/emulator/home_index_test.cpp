// [board] home switches, limit-switch positions and the encoder index: the
// switch asserts at its table position, the index latches the count at the
// mark's motor angle with an edge counter, every key off or neutral by default
// and refused out of range with its reason.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "emulator/machine.hpp"
#include "emulator/quadrature_encoder.hpp"
#include "emulator/scenario_file.hpp"
#include "hal/io_board_registers.hpp"
#include "tests/emulator/machine_register_read.hpp"

namespace tnv::emu {
namespace {

namespace regs = hal::regs;
using hal::Axis;
using test_support::read;

constexpr double kCountMm = 10.0 / 24000.0;

// Drives X open loop at the DAC code `code` (mid-scale 2048 = 0 mm/s).
void drive_x(Machine& m, std::uint32_t code) {
  ASSERT_TRUE(m.write_register(regs::kDacX, code));
  ASSERT_TRUE(m.write_register(regs::kOutputs, regs::kOutputEnableX));
}

std::uint32_t index_edges(std::uint32_t word) { return (word >> regs::kIndexEdgesShift) & regs::kIndexEdgesMask; }

TEST(IndexLatch, LatchesTheCountAtTheMarkOncePerRevolutionInEitherDirection) {
  Scenario s;
  s.board.axis[0].index_deg = 90.0;  // marks at 2.5 + k 10 mm of motor travel
  s.encoder.axis_offset_counts[0] = 1234.4;
  Machine m(s);
  const QuadratureEncoder encoder(kCountMm, s.encoder.axis_offset_counts[0]);
  EXPECT_EQ(m.index_mark_mm(Axis::x), 2.5);
  EXPECT_EQ(read(m, regs::kIndexX), 0u) << "no edge before the axis moved";

  drive_x(m, 2048 + 100);  // about +8 mm/s from x = 6 mm: marks at 12.5 and 22.5 mm
  std::uint32_t edges = 0;
  int seen = 0;
  for (int tick = 0; tick < 3000 && seen < 2; ++tick) {
    const double before_mm = m.truth(Axis::x).motor_position_mm;
    m.advance_to_next_tick();
    const std::uint32_t word = read(m, regs::kIndexX);
    if (index_edges(word) == edges) continue;
    const double mark_mm = seen == 0 ? 12.5 : 22.5;
    EXPECT_EQ(index_edges(word), edges + 1) << "one edge per mark";
    EXPECT_LE(before_mm, mark_mm) << "edge latched before the motor reached the mark";
    EXPECT_GE(m.truth(Axis::x).motor_position_mm, mark_mm) << "edge latched after the motor passed the mark";
    EXPECT_EQ(word & 0xFFFFu, encoder.register_value(mark_mm)) << "count latched at " << mark_mm << " mm";
    edges = index_edges(word);
    ++seen;
  }
  ASSERT_EQ(seen, 2) << "two marks crossed in 20 mm of travel";

  drive_x(m, 2048 - 100);  // back through 22.5 mm: the same mark latches the same count
  for (int tick = 0; tick < 3000 && index_edges(read(m, regs::kIndexX)) == edges; ++tick) m.advance_to_next_tick();
  const std::uint32_t back = read(m, regs::kIndexX);
  EXPECT_EQ(index_edges(back), edges + 1);
  EXPECT_EQ(back & 0xFFFFu, encoder.register_value(22.5)) << "the mark's count does not depend on the direction";
}

TEST(HomeSwitch, AssertsAtItsTablePositionOnItsSide) {
  Scenario s;
  s.board.axis[0].home_switch = true;
  s.board.axis[0].home_mm = 3.0;
  s.board.axis[0].home_side = -1;
  Machine m(s);
  m.advance_to_next_tick();
  EXPECT_EQ(read(m, regs::kInputs) & regs::kInputHomeX, 0u) << "released at 6 mm";
  drive_x(m, 2048 - 60);  // about -5 mm/s
  double last_released_mm = m.truth(Axis::x).position_mm;
  bool asserted = false;
  for (int tick = 0; tick < 2000 && !asserted; ++tick) {
    m.advance_to_next_tick();
    asserted = (read(m, regs::kInputs) & regs::kInputHomeX) != 0;
    if (!asserted) last_released_mm = m.truth(Axis::x).position_mm;
  }
  ASSERT_TRUE(asserted) << "the switch never asserted";
  EXPECT_LE(m.truth(Axis::x).position_mm, 3.0) << "asserted above the switch";
  EXPECT_GT(last_released_mm, 3.0) << "released below the switch";
  EXPECT_EQ(read(m, regs::kInputs) & regs::kInputHomeY, 0u) << "Y has no switch";
}

TEST(LimitSwitchPositions, AssertTheLimitInputsBeyondThem) {
  Scenario s;
  s.board.limit_switches = true;
  s.board.axis[0].limit_min_mm = 5.0;
  s.board.axis[1].limit_max_mm = -1.0;  // Y stands at 0: beyond its max
  Machine m(s);
  m.advance_to_next_tick();
  EXPECT_EQ(read(m, regs::kInputs) & (regs::kInputLimitXNeg | regs::kInputLimitXPos), 0u);
  EXPECT_NE(read(m, regs::kInputs) & regs::kInputLimitYPos, 0u);
  drive_x(m, 2048 - 60);
  for (int tick = 0; tick < 400; ++tick) m.advance_to_next_tick();
  ASSERT_LT(m.truth(Axis::x).position_mm, 5.0);
  EXPECT_NE(read(m, regs::kInputs) & regs::kInputLimitXNeg, 0u);
}

TEST(BoardKeys, PowerUpOffsetMovesTheStartAndDefaultsChangeNothing) {
  Scenario s;
  s.board.axis[0].power_up_offset_mm = -3.25;
  s.board.axis[1].power_up_offset_mm = 1.5;
  Machine moved(s);
  EXPECT_EQ(moved.truth(Axis::x).motor_position_mm, s.circle.radius_mm - 3.25);
  EXPECT_EQ(moved.truth(Axis::y).position_mm, 1.5);

  const Scenario defaults;
  EXPECT_FALSE(defaults.board.axis[0].home_switch);
  EXPECT_FALSE(defaults.board.axis[1].home_switch);
  EXPECT_FALSE(defaults.board.limit_switches);
  EXPECT_EQ(defaults.board.axis[0].power_up_offset_mm, 0.0);
  Machine m(defaults);
  m.advance_to_next_tick();
  EXPECT_EQ(read(m, regs::kInputs), 0u) << "no switch asserts by default";
}

TEST(BoardKeys, EveryKeyIsRead) {
  const ScenarioResult r = parse_scenario_text(R"(
[board]
home_switch_x = true
home_switch_y = true
home_x_mm = -12.5
home_y_mm = 30
home_x_side = 1
home_y_side = -1
index_x_deg = 45
index_y_deg = 359.5
limit_switches = true
limit_x_min_mm = -100
limit_x_max_mm = 110
limit_y_min_mm = -90
limit_y_max_mm = 95
power_up_offset_x_mm = 7
power_up_offset_y_mm = -8
)",
                                               "b.toml");
  ASSERT_TRUE(r.scenario) << r.error;
  const BoardParams& b = r.scenario->board;
  EXPECT_TRUE(b.axis[0].home_switch && b.axis[1].home_switch && b.limit_switches);
  EXPECT_EQ(b.axis[0].home_mm, -12.5);
  EXPECT_EQ(b.axis[1].home_mm, 30.0);
  EXPECT_EQ(b.axis[0].home_side, 1);
  EXPECT_EQ(b.axis[1].home_side, -1);
  EXPECT_EQ(b.axis[0].index_deg, 45.0);
  EXPECT_EQ(b.axis[1].index_deg, 359.5);
  EXPECT_EQ(b.axis[0].limit_min_mm, -100.0);
  EXPECT_EQ(b.axis[0].limit_max_mm, 110.0);
  EXPECT_EQ(b.axis[1].limit_min_mm, -90.0);
  EXPECT_EQ(b.axis[1].limit_max_mm, 95.0);
  EXPECT_EQ(b.axis[0].power_up_offset_mm, 7.0);
  EXPECT_EQ(b.axis[1].power_up_offset_mm, -8.0);
}

TEST(BoardKeys, OutOfRangeRefusedWithItsReason) {
  const struct {
    const char* text;
    const char* expected;
  } cases[] = {
      {"[board]\nhome_x_side = 0\n",
       "b.toml:2:1: board.home_x_side: must be -1 (asserted at and below home_x_mm) or 1 (at and above) (got 0)"},
      {"[board]\nindex_y_deg = 400\n", "b.toml:2:1: board.index_y_deg: must be 0..360: a motor angle in degrees (got 400)"},
      {"[board]\nhome_x_mm = nan\n",
       "b.toml:2:1: board.home_x_mm: must be -500..500: a home switch on the table's travel (got nan)"},
      {"[board]\nlimit_x_min_mm = 300\n", "b.toml:2:1: board.limit_x_min_mm: must be <= limit_x_max_mm = 200 (got 300)"},
      {"[board]\npower_up_offset_y_mm = 900\n",
       "b.toml:2:1: board.power_up_offset_y_mm: must be -500..500: where the table stands at power-up, on its travel "
       "(got 900)"},
  };
  for (const auto& c : cases) {
    const ScenarioResult r = parse_scenario_text(c.text, "b.toml");
    EXPECT_FALSE(r.scenario) << c.text;
    EXPECT_EQ(r.error, c.expected);
  }
}

}  // namespace
}  // namespace tnv::emu
