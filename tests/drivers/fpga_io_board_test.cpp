#include "drivers/fpga/fpga_io_board.hpp"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "drivers/emulated/emulated_register_bus.hpp"
#include "emulator/scenario_file.hpp"

namespace tnv::drivers {
namespace {

namespace regs = hal::regs;

// A register file that records every transfer.
class RecordingBus final : public hal::RegisterBus {
 public:
  struct Transfer {
    bool write;
    std::uint16_t first;
    std::size_t words;
  };
  std::map<std::uint16_t, std::uint32_t> regs_file{{regs::kId, regs::kIdValue}, {regs::kVersion, regs::kVersionValue}};
  std::vector<Transfer> log;
  hal::HalStatus status = hal::HalStatus::ok;

  hal::HalStatus read_block(std::uint16_t first, std::span<std::uint32_t> out) noexcept override {
    log.push_back({false, first, out.size()});
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = regs_file[static_cast<std::uint16_t>(first + i)];
    return status;
  }
  hal::HalStatus write_block(std::uint16_t first, std::span<const std::uint32_t> in) noexcept override {
    log.push_back({true, first, in.size()});
    for (std::size_t i = 0; i < in.size(); ++i) regs_file[static_cast<std::uint16_t>(first + i)] = in[i];
    return status;
  }
};

TEST(FpgaIoBoard, InitChecksTheIdAndProgramsDividerWatchdogAndSafeOutputs) {
  RecordingBus bus;
  FpgaIoBoard board(bus);
  ASSERT_TRUE(board.init({}).ok());
  EXPECT_EQ(bus.regs_file[regs::kTickDivider], 10'000u);
  EXPECT_EQ(bus.regs_file[regs::kWatchdogTimeout], 30'000u);
  EXPECT_EQ(bus.regs_file[regs::kDacX], 2048u);
  EXPECT_EQ(bus.regs_file[regs::kDacY], 2048u);
  EXPECT_EQ(bus.regs_file[regs::kDacSpindle], 2048u) << "the spindle's 0 V";
  EXPECT_EQ(bus.regs_file[regs::kOutputs], 0u);
}

TEST(FpgaIoBoard, InitRefusesA1xBoardByItsMajorVersion) {
  for (const std::uint32_t version : {0x00010004u, 0x00010000u, 0x0001FFFFu}) {
    RecordingBus bus;
    bus.regs_file[regs::kVersion] = version;
    FpgaIoBoard board(bus);
    const FpgaInitResult r = board.init({});
    EXPECT_EQ(r.status, hal::HalStatus::not_present) << std::hex << version;
    EXPECT_NE(std::string(r.message).find("I/O board 1.x"), std::string::npos) << r.message;
    EXPECT_NE(std::string(r.message).find("2.x"), std::string::npos) << r.message;
    ASSERT_EQ(bus.log.size(), 1u) << "only the identification was read";
    EXPECT_FALSE(bus.log[0].write);
    EXPECT_EQ(bus.regs_file.count(regs::kTickDivider), 0u) << "nothing written to it";
    EXPECT_EQ(bus.regs_file.count(regs::kOutputFirst), 0u) << "nothing written to it";
  }
}

TEST(FpgaIoBoard, InitRunsANewerMinorAndRefusesANewerMajor) {
  RecordingBus bus;
  bus.regs_file[regs::kVersion] = regs::kVersionValue + 1;  // a newer minor only adds registers
  EXPECT_TRUE(FpgaIoBoard(bus).init({}).ok());
  bus.regs_file[regs::kVersion] = 0x00030000;
  const FpgaInitResult r = FpgaIoBoard(bus).init({});
  EXPECT_EQ(r.status, hal::HalStatus::not_present);
  EXPECT_NE(std::string(r.message).find("unsupported I/O board major version"), std::string::npos) << r.message;
}

TEST(FpgaIoBoard, TheSpindleOutputsGoInTheTicksOneWriteAndItsChannelsComeInItsOneRead) {
  RecordingBus bus;
  FpgaIoBoard board(bus);
  ASSERT_TRUE(board.init({}).ok());
  board.set_servo_enable(hal::Axis::x, true);
  board.set_spindle_code(0x1000 | 1536);  // bits above the DAC width dropped
  board.set_spindle_reverse(true);
  board.set_spindle_enable(true);
  bus.log.clear();
  ASSERT_EQ(board.write_outputs(), hal::HalStatus::ok);
  ASSERT_EQ(bus.log.size(), 1u);
  EXPECT_EQ(bus.regs_file[regs::kDacSpindle], 1536u);
  EXPECT_EQ(bus.regs_file[regs::kOutputs],
            regs::kOutputEnableX | regs::kOutputSpindleEnable | regs::kOutputSpindleReverse);
  board.set_spindle_enable(false);
  board.set_spindle_reverse(false);
  ASSERT_EQ(board.write_outputs(), hal::HalStatus::ok);
  EXPECT_EQ(bus.regs_file[regs::kOutputs], regs::kOutputEnableX) << "the axis' enable untouched";

  bus.regs_file[regs::kSpindleEncoder] = 0x1'ABCD;  // bits above the counter width ignored
  bus.regs_file[regs::kSpindleIndex] = 0x1000 | (7u << regs::kIndexEdgesShift);
  bus.log.clear();
  ASSERT_EQ(board.read_inputs(), hal::HalStatus::ok);
  ASSERT_EQ(bus.log.size(), 1u);
  EXPECT_EQ(board.spindle_latched_count(), 0xABCDu);
  EXPECT_EQ(board.spindle_index_latch().count, 0x1000u);
  EXPECT_EQ(board.spindle_index_latch().edges, 7u);
}

TEST(FpgaIoBoard, InitRefusesAMissingOrForeignBoard) {
  RecordingBus bus;
  bus.regs_file[regs::kId] = 0xDEADBEEF;
  FpgaIoBoard board(bus);
  const FpgaInitResult r = board.init({});
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.status, hal::HalStatus::not_present);
  EXPECT_NE(std::string(r.message).find("id"), std::string::npos);
  EXPECT_EQ(bus.regs_file.count(regs::kTickDivider), 0u) << "nothing written to a foreign board";

  RecordingBus dead;
  dead.status = hal::HalStatus::timeout;
  FpgaIoBoard board2(dead);
  EXPECT_EQ(board2.init({}).status, hal::HalStatus::timeout);
  EXPECT_FALSE(FpgaIoBoard(bus).init({.tick_divider_clocks = 10'000, .watchdog_timeout_clocks = 5'000}).ok());
}

TEST(FpgaIoBoard, OneBatchedReadAndOneBatchedWritePerTick) {
  RecordingBus bus;
  FpgaIoBoard board(bus);
  ASSERT_TRUE(board.init({}).ok());
  bus.log.clear();
  ASSERT_EQ(board.read_inputs(), hal::HalStatus::ok);
  board.set_code(hal::Axis::x, 3000);
  board.set_code(hal::Axis::y, 100);
  board.set_servo_enable(hal::Axis::y, true);
  board.kick();
  ASSERT_EQ(board.write_outputs(), hal::HalStatus::ok);
  ASSERT_EQ(bus.log.size(), 2u);
  EXPECT_FALSE(bus.log[0].write);
  EXPECT_EQ(bus.log[0].first, regs::kSnapshotFirst);
  EXPECT_EQ(bus.log[0].words, regs::kSnapshotWords);
  EXPECT_TRUE(bus.log[1].write);
  EXPECT_EQ(bus.log[1].first, regs::kOutputFirst);
  EXPECT_EQ(bus.log[1].words, regs::kOutputWords);
  // The board's words and three snapshot words and one DAC per axis of the
  // list: 14 and 5 with two axes, as the 1.x map read and wrote.
  EXPECT_EQ(regs::kSnapshotWords, 8u + 3u * hal::kAxisCount);
  EXPECT_EQ(regs::kOutputWords, 3u + hal::kAxisCount);
  EXPECT_EQ(bus.regs_file[regs::kDacX], 3000u);
  EXPECT_EQ(bus.regs_file[regs::kDacY], 100u);
  EXPECT_EQ(bus.regs_file[regs::kOutputs], regs::kOutputEnableY);
  EXPECT_EQ(bus.regs_file[regs::kWatchdogKick], regs::kWatchdogKickKey);
  // Without a new kick() the next write does not kick.
  board.write_outputs();
  EXPECT_EQ(bus.regs_file[regs::kWatchdogKick], 0u);
}

TEST(FpgaIoBoard, DecodesTheSnapshotWindow) {
  RecordingBus bus;
  bus.regs_file[regs::kTickSequence] = 77;
  bus.regs_file[regs::kTickClock] = 0xFFFFFF00u;
  bus.regs_file[regs::kEncoderX] = 0x1234;
  bus.regs_file[regs::kEncoderY] = 0xFFFF;
  bus.regs_file[regs::kInputs] =
      regs::kInputEstop | regs::kInputAlarmY | regs::kInputLimitXNeg | regs::kInputWatchdogTripped | regs::kInputProbe;
  bus.regs_file[regs::kAdcForce] = 4095;
  bus.regs_file[regs::kAdcAccelX] = 0x1000 | 2100;  // bits above the ADC width ignored
  bus.regs_file[regs::kAdcAccelY] = 17;
  FpgaIoBoard board(bus);
  ASSERT_EQ(board.read_inputs(), hal::HalStatus::ok);
  EXPECT_EQ(board.latched_tick().sequence, 77u);
  EXPECT_EQ(board.latched_tick().clock_10mhz, 0xFFFFFF00u);
  EXPECT_EQ(board.latched_count(hal::Axis::x), 0x1234u);
  EXPECT_EQ(board.latched_count(hal::Axis::y), 0xFFFFu);
  const hal::DiscreteInputs in = board.inputs();
  EXPECT_TRUE(in.estop);
  EXPECT_FALSE(in.servo_alarm[0]);
  EXPECT_TRUE(in.servo_alarm[1]);
  EXPECT_TRUE(in.limit_negative[0]);
  EXPECT_FALSE(in.limit_positive[0]);
  EXPECT_TRUE(in.watchdog_tripped);
  EXPECT_TRUE(in.probe);
  EXPECT_EQ(board.latched_force_code(), 4095);
  EXPECT_EQ(board.latched_accel_code(hal::Axis::x), 2100);
  EXPECT_EQ(board.latched_accel_code(hal::Axis::y), 17);
}

TEST(EmulatedRegisterBus, TheDriverRunsAgainstTheEmulatedBoard) {
  emu::Machine machine(*emu::builtin_scenario("no-cut"));
  EmulatedRegisterBus bus(machine);
  FpgaIoBoard board(bus);
  ASSERT_TRUE(board.init({}).ok());
  machine.advance_to_next_tick();
  ASSERT_EQ(board.read_inputs(), hal::HalStatus::ok);
  const auto first = board.latched_tick();
  machine.advance_to_next_tick();
  ASSERT_EQ(board.read_inputs(), hal::HalStatus::ok);
  const auto second = board.latched_tick();
  EXPECT_EQ(second.sequence - first.sequence, 1u);
  EXPECT_EQ(second.clock_10mhz - first.clock_10mhz, 10'000u);
  // Table at (6, 0) mm: 14,400 counts on X.
  EXPECT_EQ(board.latched_count(hal::Axis::x), 14'400u);
  std::array<std::uint32_t, 1> junk{};
  EXPECT_EQ(bus.read_block(0x3FF, junk), hal::HalStatus::bad_address);
}

}  // namespace
}  // namespace tnv::drivers
