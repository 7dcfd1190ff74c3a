// Each axis of the list on its slot of the 2.0 board, end to end: the FPGA
// driver writes the axis' DAC and enable and reads its encoder, accelerometer,
// index and input bits over the emulated register bus, and the emulated
// board holds them at the addresses of the axis' row (kAxisRegisters).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>

#include "drivers/emulated/emulated_register_bus.hpp"
#include "drivers/fpga/fpga_io_board.hpp"
#include "emulator/machine.hpp"
#include "emulator/scenario_file.hpp"
#include "hal/io_board_registers.hpp"

namespace tnv::drivers {
namespace {

namespace regs = hal::regs;

struct SlotBench {
  emu::Machine machine{*emu::builtin_scenario("no-cut")};
  EmulatedRegisterBus bus{machine};
  FpgaIoBoard board{bus};

  std::uint32_t board_word(std::uint16_t word) {
    std::uint32_t value = 0;
    EXPECT_TRUE(machine.read_register(word, value)) << "0x" << std::hex << word;
    return value;
  }

  void tick() {
    board.kick();
    EXPECT_EQ(board.write_outputs(), hal::HalStatus::ok);
    machine.advance_to_next_tick();
    EXPECT_EQ(board.read_inputs(), hal::HalStatus::ok);
  }
};

TEST(FpgaAxisSlots, EachAxisRowReadsAndWritesThroughTheDriverOnTheEmulatedBoard) {
  constexpr std::uint16_t kMid = 2048;
  for (const hal::Axis moved : hal::kAxes) {
    SlotBench b;
    ASSERT_TRUE(b.board.init({}).ok());
    b.tick();
    std::array<std::uint32_t, hal::kAxisCount> start{};
    for (const hal::Axis a : hal::kAxes) start[hal::index(a)] = b.board.latched_count(a);

    b.board.set_code(moved, kMid + 400);  // about 33 mm/s
    b.board.set_servo_enable(moved, true);
    for (int k = 0; k < 50; ++k) b.tick();

    const regs::AxisRegisters& row = regs::axis_registers(moved);
    EXPECT_EQ(b.board_word(row.dac), kMid + 400u) << hal::axis_label(moved);
    EXPECT_EQ(b.board_word(regs::kOutputs), row.output_enable) << hal::axis_label(moved);
    for (const hal::Axis a : hal::kAxes) {
      const regs::AxisRegisters& r = regs::axis_registers(a);
      EXPECT_EQ(b.board.latched_count(a), b.board_word(r.encoder) & 0xFFFFu) << hal::axis_label(a);
      EXPECT_EQ(b.board.latched_accel_code(a), b.board_word(r.adc_accel)) << hal::axis_label(a);
      const hal::IndexLatch latch = b.board.index_latch(a);
      EXPECT_EQ(latch.count | (std::uint32_t{latch.edges} << regs::kIndexEdgesShift), b.board_word(r.index))
          << hal::axis_label(a);
      if (a == moved) {
        EXPECT_NE(b.board.latched_count(a), start[hal::index(a)]) << hal::axis_label(a) << " moves on its own DAC";
      } else {
        EXPECT_EQ(b.board_word(r.dac), kMid) << hal::axis_label(a);
        EXPECT_EQ(b.board.latched_count(a), start[hal::index(a)]) << hal::axis_label(a) << " holds still";
      }
    }

    // The axis' input bits come back on its own row only.
    b.machine.set_servo_alarm(moved, true);
    b.machine.set_limit(moved, true, true);
    b.tick();
    const hal::DiscreteInputs in = b.board.inputs();
    for (const hal::Axis a : hal::kAxes) {
      EXPECT_EQ(in.servo_alarm[hal::index(a)], a == moved) << hal::axis_label(a);
      EXPECT_EQ(in.limit_positive[hal::index(a)], a == moved) << hal::axis_label(a);
      EXPECT_FALSE(in.limit_negative[hal::index(a)]) << hal::axis_label(a);
    }
    EXPECT_EQ(b.board_word(regs::kInputs) & (row.input_alarm | row.input_limit_pos),
              row.input_alarm | row.input_limit_pos);
  }
}

TEST(FpgaAxisSlots, TheSlotsBeyondTheListAndTheGapsAreUnmappedOnTheEmulatedBoard) {
  emu::Machine machine(*emu::builtin_scenario("no-cut"));
  EmulatedRegisterBus bus(machine);
  std::array<std::uint32_t, 1> word{};
  for (std::size_t slot = hal::kAxisCount; slot < regs::kMaxAxes; ++slot) {
    const regs::AxisRegisters r = regs::axis_slot(slot);
    for (const std::uint16_t reg : {r.encoder, r.adc_accel, r.index, r.dac}) {
      EXPECT_EQ(bus.read_block(reg, word), hal::HalStatus::bad_address) << "0x" << std::hex << reg;
      EXPECT_EQ(bus.write_block(reg, word), hal::HalStatus::bad_address) << "0x" << std::hex << reg;
    }
  }
  // One word past the tick's read and past its write: the block is refused whole.
  std::array<std::uint32_t, regs::kSnapshotWords + 1> longer_read{};
  EXPECT_EQ(bus.read_block(regs::kSnapshotFirst, longer_read), hal::HalStatus::bad_address);
  std::array<std::uint32_t, regs::kOutputWords + 1> longer_write{};
  longer_write.fill(2048);
  longer_write[regs::kOutputs - regs::kOutputFirst] = 0;
  EXPECT_EQ(bus.write_block(regs::kOutputFirst, longer_write), hal::HalStatus::bad_address);
}

}  // namespace
}  // namespace tnv::drivers
