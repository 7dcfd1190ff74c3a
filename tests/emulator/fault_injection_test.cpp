// Each scheduled fault does what it says at the register door of the
// emulated machine, from its start to its end, and nothing else.
#include <gtest/gtest.h>

#include <cmath>

#include "emulator/dac_speed_map.hpp"
#include "emulator/fault_timeline.hpp"
#include "emulator/machine.hpp"
#include "emulator/quadrature_encoder.hpp"
#include "emulator/scenario_validation.hpp"
#include "hal/io_board_registers.hpp"
#include "tests/emulator/machine_register_read.hpp"

namespace tnv::emu {
namespace {

namespace regs = hal::regs;
using hal::Axis;

using test_support::read;

Scenario with_fault(const FaultSpec& f) {
  Scenario s;
  s.plant[0].coulomb_mm_s = s.plant[0].stiction_mm_s = 0.0;  // friction off: speed = command exactly
  s.plant[1].coulomb_mm_s = s.plant[1].stiction_mm_s = 0.0;
  s.faults.push_back(f);
  EXPECT_EQ(validate_scenario(s), "");
  return s;
}

void drive(Machine& m, int dac_x_offset, int dac_y_offset = 0) {
  ASSERT_TRUE(m.write_register(regs::kDacX, static_cast<std::uint32_t>(2048 + dac_x_offset)));
  ASSERT_TRUE(m.write_register(regs::kDacY, static_cast<std::uint32_t>(2048 + dac_y_offset)));
  ASSERT_TRUE(m.write_register(regs::kOutputs, regs::kOutputEnableX | regs::kOutputEnableY));
}

// What the decoder of a healthy board would hold for the table's true position.
std::uint32_t healthy_count(const Machine& m, Axis axis) {
  const Scenario& s = m.scenario();
  const QuadratureEncoder encoder(s.encoder.count_mm(), s.encoder.offset_counts(axis));
  return encoder.register_value(m.truth(axis).position_mm);
}

std::uint32_t count_difference(std::uint32_t a, std::uint32_t b) { return (a - b) & 0xFFFFu; }

TEST(FaultTimeline, EdgesLandOnTheSubstepGridInOrder) {
  std::vector<FaultSpec> faults(3);
  faults[0] = {.kind = FaultKind::estop, .start_s = 0.003, .duration_s = 0.002};
  faults[1] = {.kind = FaultKind::late_tick, .start_s = 0.0030001, .duration_s = 5.0, .delay_us = 10};
  faults[2] = {.kind = FaultKind::estop, .start_s = 0.005};
  FaultTimeline t(faults);
  ASSERT_EQ(t.edges().size(), 4u) << "late_tick is one-shot: its duration is not an edge";
  EXPECT_EQ(t.edges()[0].substep, 300u);
  EXPECT_EQ(t.edges()[1].substep, 301u) << "start_s rounds up to the next 10 us boundary";
  EXPECT_EQ(t.edges()[2].substep, 500u);
  EXPECT_FALSE(t.edges()[2].begins) << "at one boundary the end of a window comes before a begin";
  EXPECT_EQ(t.edges()[3].fault, 2u);
  EXPECT_EQ(t.substeps_to_next(0), 300u);
  EXPECT_EQ(t.take_due(299).size(), 0u);
  EXPECT_EQ(t.take_due(301).size(), 2u);
  EXPECT_EQ(t.substeps_to_next(301), 199u);
  EXPECT_EQ(t.take_due(10'000).size(), 2u);
  EXPECT_EQ(t.substeps_to_next(10'000), FaultTimeline::kNever);
}

TEST(FaultInjection, EstopWindowAssertsTheInputFromStartToEnd) {
  Machine m(with_fault({.kind = FaultKind::estop, .start_s = 0.0035, .duration_s = 0.002}));
  std::uint32_t seen[7];
  for (std::uint32_t& inputs : seen) {
    m.advance_to_next_tick();
    inputs = read(m, regs::kInputs);
  }
  // Latches at 1..7 ms; the window is [3.5, 5.5) ms.
  const std::uint32_t want[7] = {0, 0, 0, regs::kInputEstop, regs::kInputEstop, 0, 0};
  for (int i = 0; i < 7; ++i) EXPECT_EQ(seen[i], want[i]) << "tick at " << i + 1 << " ms";
  EXPECT_FALSE(m.fault_active(0));
}

TEST(FaultInjection, AlarmAndLimitAssertTheirOwnAxisBitsToTheEnd) {
  Scenario s;
  s.faults.push_back({.kind = FaultKind::servo_alarm, .start_s = 0.001, .axis = Axis::y});
  s.faults.push_back({.kind = FaultKind::limit_switch, .start_s = 0.002, .axis = Axis::x, .positive_side = false});
  s.faults.push_back({.kind = FaultKind::limit_switch, .start_s = 0.002, .axis = Axis::y, .positive_side = true});
  Machine m(s);
  m.advance_to_next_tick();  // 1 ms: the alarm starts on this boundary, after the latch
  EXPECT_EQ(read(m, regs::kInputs), 0u);
  m.advance_to_next_tick();
  EXPECT_EQ(read(m, regs::kInputs), regs::kInputAlarmY);
  for (int i = 0; i < 50; ++i) m.advance_to_next_tick();
  EXPECT_EQ(read(m, regs::kInputs), regs::kInputAlarmY | regs::kInputLimitXNeg | regs::kInputLimitYPos)
      << "no duration: asserted to the end of the run";
}

TEST(FaultInjection, IllegalTransitionLatchesTheFaultAndLosesTwoCounts) {
  Machine m(with_fault({.kind = FaultKind::encoder_illegal, .start_s = 0.0105, .axis = Axis::x}));
  drive(m, 200);  // about +16 mm/s
  for (int i = 0; i < 10; ++i) m.advance_to_next_tick();
  EXPECT_EQ(read(m, regs::kFaults), 0u);
  EXPECT_EQ(read(m, regs::kEncoderX), healthy_count(m, Axis::x));
  m.advance_to_next_tick();
  EXPECT_EQ(read(m, regs::kFaults), regs::kFaultEncoderX);
  EXPECT_EQ(count_difference(healthy_count(m, Axis::x), read(m, regs::kEncoderX)), 2u)
      << "the register lags the table by the 2 uncounted states";
  for (int i = 0; i < 10; ++i) m.advance_to_next_tick();
  EXPECT_EQ(read(m, regs::kFaults), regs::kFaultEncoderX) << "sticky";
  EXPECT_EQ(count_difference(healthy_count(m, Axis::x), read(m, regs::kEncoderX)), 2u) << "counts again, 2 behind";
  EXPECT_EQ(read(m, regs::kEncoderY), healthy_count(m, Axis::y)) << "the other axis is untouched";
  ASSERT_TRUE(m.write_register(regs::kControl, regs::kControlClearFaults));
  m.advance_to_next_tick();
  EXPECT_EQ(read(m, regs::kFaults), 0u);
}

TEST(FaultInjection, DeadEncoderFreezesTheCountThenCountsOnFromThere) {
  Machine m(with_fault({.kind = FaultKind::encoder_dead, .start_s = 0.0100, .duration_s = 0.005, .axis = Axis::y}));
  drive(m, 0, -150);
  for (int i = 0; i < 10; ++i) m.advance_to_next_tick();
  const std::uint32_t frozen = read(m, regs::kEncoderY);
  EXPECT_EQ(frozen, healthy_count(m, Axis::y));
  const double p0_mm = m.truth(Axis::y).position_mm;
  for (int i = 0; i < 5; ++i) {
    m.advance_to_next_tick();
    EXPECT_EQ(read(m, regs::kEncoderY), frozen) << "dead at tick " << i;
  }
  const double moved_mm = m.truth(Axis::y).position_mm - p0_mm;
  EXPECT_LT(moved_mm, -0.04) << "the table kept moving while the encoder was dead";
  for (int i = 0; i < 5; ++i) m.advance_to_next_tick();
  const auto lost = static_cast<std::int16_t>(count_difference(healthy_count(m, Axis::y), read(m, regs::kEncoderY)));
  EXPECT_NEAR(lost * m.scenario().encoder.count_mm(), moved_mm, 2 * m.scenario().encoder.count_mm())
      << "after the lines come back the count is short by the motion it missed";
  EXPECT_EQ(read(m, regs::kFaults), 0u) << "a dead encoder makes no illegal transition";
}

TEST(FaultInjection, StuckDacDrivesItsCodeAndTheReadbackLatchesAFault) {
  Machine m(with_fault({.kind = FaultKind::dac_stuck, .start_s = 0.0025, .duration_s = 0.003, .axis = Axis::x,
                        .dac_code = 3000}));
  const DacSpeedMap dac(m.scenario().dac, m.scenario().encoder.lead_mm);
  drive(m, 100);
  m.advance_to_next_tick();
  m.advance_to_next_tick();
  EXPECT_EQ(m.truth(Axis::x).dac_output_code, 2148u);
  m.advance_to_next_tick();  // 3 ms: stuck since 2.5 ms
  EXPECT_EQ(m.truth(Axis::x).dac_output_code, 3000u);
  EXPECT_EQ(read(m, regs::kDacX), 2148u) << "the register keeps what was written";
  EXPECT_DOUBLE_EQ(m.truth(Axis::x).command_mm_s, dac.speed_mm_s(3000)) << "the servopack sees the stuck output";
  EXPECT_EQ(read(m, regs::kFaults), regs::kFaultDacX) << "readback 3000 vs register 2148";
  ASSERT_TRUE(m.write_register(regs::kOutputs, 0));
  m.advance_clocks(100);
  EXPECT_EQ(m.truth(Axis::x).command_mm_s, 0.0) << "the enable still removes the drive";
  for (int i = 0; i < 3; ++i) m.advance_to_next_tick();  // window ends at 5.5 ms
  EXPECT_EQ(m.truth(Axis::x).dac_output_code, 2148u);
  EXPECT_EQ(read(m, regs::kFaults), regs::kFaultDacX) << "sticky";
}

TEST(FaultInjection, StuckDacAtTheWrittenCodeIsNotAFault) {
  Machine m(with_fault({.kind = FaultKind::dac_stuck, .start_s = 0.0, .axis = Axis::y, .dac_code = 2048 + 3}));
  drive(m, 0, 0);
  for (int i = 0; i < 5; ++i) m.advance_to_next_tick();
  EXPECT_EQ(read(m, regs::kFaults), 0u) << "3 LSB apart is within the comparator's tolerance";
  ASSERT_TRUE(m.write_register(regs::kDacY, 2048 - 2));
  m.advance_to_next_tick();
  EXPECT_EQ(read(m, regs::kFaults), regs::kFaultDacY) << "5 LSB apart";
}

TEST(FaultInjection, MissedTicksAreSleptThrough) {
  Machine m(with_fault({.kind = FaultKind::missed_tick, .start_s = 0.0025, .ticks = 3}));
  m.advance_to_next_tick();
  m.advance_to_next_tick();
  EXPECT_EQ(read(m, regs::kTickSequence), 1u);
  m.advance_to_next_tick();  // latches at 3, 4, 5 ms are lost
  EXPECT_EQ(read(m, regs::kTickSequence), 5u);
  EXPECT_EQ(read(m, regs::kTickClock), 60'000u);
  EXPECT_EQ(m.elapsed_clocks(), 60'000u);
  m.advance_to_next_tick();
  EXPECT_EQ(read(m, regs::kTickSequence), 6u) << "one-shot";
}

TEST(FaultInjection, LateTickLatchesLateAndTheTimerKeepsItsPeriodFromThere) {
  Machine m(with_fault({.kind = FaultKind::late_tick, .start_s = 0.0015, .delay_us = 1500}));
  m.advance_to_next_tick();
  m.advance_to_next_tick();  // nominal 2 ms, 1.5 ms late
  EXPECT_EQ(read(m, regs::kTickSequence), 1u);
  EXPECT_EQ(read(m, regs::kTickClock), 35'000u);
  m.advance_to_next_tick();
  EXPECT_EQ(read(m, regs::kTickSequence), 2u);
  EXPECT_EQ(read(m, regs::kTickClock), 45'000u);
}

TEST(FaultInjection, StaleSnapshotKeepsTicksFiringButTheWindowFrozen) {
  Machine m(with_fault({.kind = FaultKind::stale_snapshot, .start_s = 0.0015, .duration_s = 0.002}));
  drive(m, 100);
  m.advance_to_next_tick();
  m.advance_to_next_tick();  // 2 ms
  EXPECT_EQ(read(m, regs::kTickSequence), 0u);
  EXPECT_EQ(read(m, regs::kTickClock), 10'000u);
  const std::uint32_t encoder = read(m, regs::kEncoderX);
  m.advance_to_next_tick();  // 3 ms
  EXPECT_EQ(m.elapsed_clocks(), 30'000u) << "the tick still fires";
  EXPECT_EQ(read(m, regs::kTickSequence), 0u);
  EXPECT_EQ(read(m, regs::kEncoderX), encoder);
  m.advance_to_next_tick();  // 4 ms: the window [1.5, 3.5) ms is over
  EXPECT_EQ(read(m, regs::kTickSequence), 1u);
  EXPECT_EQ(read(m, regs::kTickClock), 40'000u);
  EXPECT_EQ(read(m, regs::kEncoderX), healthy_count(m, Axis::x));
}

TEST(FaultInjection, RunawayDriveMovesAgainstTheCommand) {
  Machine m(with_fault({.kind = FaultKind::runaway, .start_s = 0.005, .axis = Axis::x}));
  drive(m, 100, 100);
  for (int i = 0; i < 5; ++i) m.advance_to_next_tick();
  EXPECT_GT(m.truth(Axis::x).speed_mm_s, 3.0) << "mm/s, with the command";
  for (int i = 0; i < 50; ++i) m.advance_to_next_tick();
  const DacSpeedMap dac(m.scenario().dac, m.scenario().encoder.lead_mm);
  EXPECT_NEAR(m.truth(Axis::x).speed_mm_s, -dac.speed_mm_s(2148), 0.01) << "gain sign flipped, mm/s";
  EXPECT_NEAR(m.truth(Axis::y).speed_mm_s, dac.speed_mm_s(2148), 0.01) << "Y untouched, mm/s";
}

TEST(FaultInjection, BusReadErrorsFailEveryReadInTheWindowOnly) {
  Machine m(with_fault({.kind = FaultKind::bus_read_error, .start_s = 0.0015, .duration_s = 0.001}));
  std::uint32_t value = 0;
  m.advance_to_next_tick();
  EXPECT_TRUE(m.read_register(regs::kTickSequence, value));
  m.advance_to_next_tick();
  EXPECT_FALSE(m.read_register(regs::kTickSequence, value));
  EXPECT_FALSE(m.read_register(regs::kId, value));
  EXPECT_TRUE(m.write_register(regs::kDacX, 2048)) << "writes still go through";
  m.advance_to_next_tick();
  EXPECT_TRUE(m.read_register(regs::kTickSequence, value));
  EXPECT_EQ(value, 2u);
}

}  // namespace
}  // namespace tnv::emu
