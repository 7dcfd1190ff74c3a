// The ball screw between the motor (encoder) and the table: backlash as
// lost motion on a reversal, lead error as the gap between what the
// encoder counts and where the table is.
#include "emulator/screw_transmission.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "emulator/machine.hpp"
#include "emulator/quadrature_encoder.hpp"
#include "hal/io_board_registers.hpp"
#include "tests/emulator/machine_register_read.hpp"

namespace tnv::emu {
namespace {

namespace regs = hal::regs;
using hal::Axis;
using test_support::read;

constexpr double kUm = 1e-3;  // mm

TEST(ScrewTransmission, OffIsTheMotorSideExactly) {
  const ScrewTransmission screw(AxisPlantParams{}, 6.0);
  EXPECT_FALSE(screw.enabled());
  EXPECT_EQ(screw.table_mm(1.2345678), 1.2345678);
}

TEST(ScrewTransmission, PlayOperatorLosesTheLashOnEachReversal) {
  AxisPlantParams p;
  p.backlash_um = 8.0;
  ScrewTransmission screw(p, 0.0);
  // Centred at power-up: the first 4 um of motion in either direction are lost.
  screw.follow(3.0 * kUm);
  EXPECT_EQ(screw.table_mm(3.0 * kUm), 0.0) << "inside the half lash the table stays";
  screw.follow(1.0);
  EXPECT_NEAR(screw.table_mm(1.0), 1.0 - 4.0 * kUm, 1e-12) << "pushed: the table trails by half the lash";
  // Reverse: the table stands still while the motor crosses the whole lash.
  screw.follow(1.0 - 7.9 * kUm);
  EXPECT_NEAR(screw.table_mm(1.0 - 7.9 * kUm), 1.0 - 4.0 * kUm, 1e-12) << "7.9 um back: still inside the 8 um lash";
  screw.follow(0.5);
  EXPECT_NEAR(screw.table_mm(0.5), 0.5 + 4.0 * kUm, 1e-12) << "pulled back: the table leads by half the lash";
}

TEST(ScrewTransmission, LeadErrorIsCumulativePlusPeriodic) {
  AxisPlantParams p;
  p.lead_error_um_per_m = 50.0;
  p.pitch_error_um = 3.0;
  p.pitch_period_mm = 10.0;
  const ScrewTransmission screw(p, 0.0);
  EXPECT_EQ(screw.table_mm(0.0), 0.0) << "both errors are zero at the machine origin";
  // 200 mm of travel: 50 um/m -> 10 um, plus 3 um sin(2 pi 2.5 / 10) = 3 um at 202.5 mm.
  EXPECT_NEAR(screw.table_mm(202.5) - 202.5, (50.0 * 0.2025 + 3.0) * kUm, 1e-12);
  EXPECT_NEAR(screw.table_mm(-7.5) + 7.5, (50.0 * -0.0075 + 3.0) * kUm, 1e-12) << "sin(2 pi (-0.75)) = +1";
}

void servo_on_x(Machine& m, std::uint32_t dac_x) {
  ASSERT_TRUE(m.write_register(regs::kDacX, dac_x));
  ASSERT_TRUE(m.write_register(regs::kOutputs, regs::kOutputEnableX));
}

// The motor (what the encoder counts) moves +, then reverses: the table
// loses exactly the lash, which the encoder never sees.
TEST(ScrewTransmissionOnMachine, BacklashIsLostMotionOfItsWidthOnAReversal) {
  Scenario s;
  s.plant[0].backlash_um = 10.0;
  Machine m(s);
  const std::uint32_t mid = m.dac_mid_code();
  servo_on_x(m, mid + 100);  // about +8.1 mm/s
  m.advance_clocks(200'000);  // 20 ms
  AxisTruth t = m.truth(Axis::x);
  ASSERT_GT(t.motor_position_mm, 6.05);
  EXPECT_NEAR(t.position_mm - t.motor_position_mm, -5.0 * kUm, 1e-12) << "pushing +: the table trails by b/2";

  servo_on_x(m, mid - 100);
  // The speed loop takes a few ms to turn the motor round; the table follows it up to its turning point.
  double motor_max_mm = t.motor_position_mm, table_max_mm = t.position_mm;
  double motor_when_table_moved_mm = 0.0;
  for (int k = 0; k < 4000 && motor_when_table_moved_mm == 0.0; ++k) {  // 10 us at a time, up to 40 ms
    m.advance_clocks(100);
    t = m.truth(Axis::x);
    motor_max_mm = std::max(motor_max_mm, t.motor_position_mm);
    table_max_mm = std::max(table_max_mm, t.position_mm);
    if (t.position_mm < table_max_mm - 1e-9) motor_when_table_moved_mm = t.motor_position_mm;
  }
  EXPECT_NEAR(table_max_mm, motor_max_mm - 5.0 * kUm, 1e-12);
  ASSERT_NE(motor_when_table_moved_mm, 0.0) << "the table never followed the reversal";
  // It moves in the first sub-step after the motor is 10 um back from its turning point (at 8 mm/s a
  // sub-step is 0.08 um of travel).
  const double lost_um = (motor_max_mm - motor_when_table_moved_mm) / kUm;
  EXPECT_GT(lost_um, 10.0) << "lost motion " << lost_um << " um, lash 10 um";
  EXPECT_LT(lost_um, 10.1) << "lost motion " << lost_um << " um, lash 10 um";
  m.advance_clocks(200'000);
  t = m.truth(Axis::x);
  EXPECT_NEAR(t.position_mm - t.motor_position_mm, +5.0 * kUm, 1e-12) << "pulling -: the table leads by b/2";
  // The encoder follows the motor, not the table.
  const QuadratureEncoder encoder(s.encoder.count_mm(), 0.0);
  m.advance_to_next_tick();
  EXPECT_EQ(read(m, regs::kEncoderX), encoder.register_value(m.truth(Axis::x).motor_position_mm));
}

TEST(ScrewTransmissionOnMachine, LeadErrorShiftsTheTableFromWhatTheEncoderCounts) {
  Scenario s;
  s.plant[0].lead_error_um_per_m = 1000.0;
  s.plant[0].pitch_error_um = 2.0;
  s.plant[0].pitch_period_mm = 10.0;
  Machine m(s);
  const auto expected_gap_mm = [](double e_mm) {
    return 1000e-6 * e_mm + 2.0 * kUm * std::sin(2.0 * std::numbers::pi * e_mm / 10.0);
  };
  AxisTruth t = m.truth(Axis::x);
  EXPECT_EQ(t.motor_position_mm, 6.0);
  EXPECT_NEAR(t.position_mm - 6.0, expected_gap_mm(6.0), 1e-12);
  EXPECT_EQ(m.truth(Axis::y).position_mm, 0.0) << "Y has no lead error";

  servo_on_x(m, m.dac_mid_code() + 1000);  // about 81 mm/s
  for (int i = 0; i < 50; ++i) m.advance_to_next_tick();
  t = m.truth(Axis::x);
  ASSERT_GT(t.motor_position_mm, 8.0);
  EXPECT_NEAR(t.position_mm - t.motor_position_mm, expected_gap_mm(t.motor_position_mm), 1e-12);
  const QuadratureEncoder encoder(s.encoder.count_mm(), 0.0);
  EXPECT_EQ(read(m, regs::kEncoderX), encoder.register_value(t.motor_position_mm)) << "the encoder counts the motor";
  EXPECT_NE(encoder.register_value(t.motor_position_mm), encoder.register_value(t.position_mm))
      << "and here the table is counts away from it";
}

}  // namespace
}  // namespace tnv::emu
