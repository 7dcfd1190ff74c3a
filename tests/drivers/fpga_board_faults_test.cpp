// The board's FAULTS word through the driver: decoded into the inputs the
// supervisor sees, and cleared by the explicit clear on the real bus path.
#include <gtest/gtest.h>

#include "drivers/emulated/emulated_register_bus.hpp"
#include "drivers/fpga/fpga_io_board.hpp"
#include "emulator/machine.hpp"
#include "emulator/scenario_file.hpp"

namespace tnv::drivers {
namespace {

namespace regs = hal::regs;

TEST(FpgaBoardFaults, FaultBitsAppearAsPerAxisInputsAndClearOnCommand) {
  emu::Scenario s = *emu::builtin_scenario("no-cut");
  s.faults.push_back({.kind = emu::FaultKind::encoder_illegal, .start_s = 0.0015, .axis = hal::Axis::y});
  s.faults.push_back(
      {.kind = emu::FaultKind::dac_stuck, .start_s = 0.0015, .duration_s = 0.001, .axis = hal::Axis::x, .dac_code = 0});
  emu::Machine machine(s);
  EmulatedRegisterBus bus(machine);
  FpgaIoBoard board(bus);
  ASSERT_TRUE(board.init({}).ok());
  machine.advance_to_next_tick();
  ASSERT_EQ(board.read_inputs(), hal::HalStatus::ok);
  EXPECT_FALSE(board.inputs().encoder_error[1]);
  machine.advance_to_next_tick();
  ASSERT_EQ(board.read_inputs(), hal::HalStatus::ok);
  const hal::DiscreteInputs in = board.inputs();
  EXPECT_FALSE(in.encoder_error[0]);
  EXPECT_TRUE(in.encoder_error[1]);
  EXPECT_TRUE(in.dac_error[0]) << "DAC X stuck at 0 while its register holds mid-scale";
  EXPECT_FALSE(in.dac_error[1]);
  EXPECT_EQ(board.latched_fault_bits(), regs::kFaultEncoderY | regs::kFaultDacX);

  machine.advance_to_next_tick();  // the DAC window is over; the latch stays
  ASSERT_EQ(board.read_inputs(), hal::HalStatus::ok);
  EXPECT_TRUE(board.inputs().dac_error[0]);
  ASSERT_EQ(board.clear_latched_faults(), hal::HalStatus::ok);
  machine.advance_to_next_tick();
  ASSERT_EQ(board.read_inputs(), hal::HalStatus::ok);
  EXPECT_EQ(board.latched_fault_bits(), 0u);
  EXPECT_FALSE(board.inputs().dac_error[0]);
  EXPECT_FALSE(board.inputs().encoder_error[1]);
}

}  // namespace
}  // namespace tnv::drivers
