// The I/O board at register level: counter, tick latch, DAC, outputs,
// watchdog and access rules (hal/io_board_registers.hpp).
#include "emulator/io_board.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace tnv::emu {
namespace {

namespace regs = hal::regs;
using hal::Axis;

IoBoard make_board(std::uint32_t clock_start = 0) { return IoBoard(BoardParams{clock_start}, DacParams{}, 10.0); }

std::uint32_t read(const IoBoard& board, std::uint16_t word) {
  std::uint32_t value = 0xDEADBEEF;
  EXPECT_TRUE(board.read_register(word, value)) << "read of 0x" << std::hex << word;
  return value;
}

// Runs sub-steps, latching ticks like the machine does; returns ticks latched.
int run(IoBoard& board, int substeps, std::uint32_t encoder_x = 0) {
  int ticks = 0;
  for (int i = 0; i < substeps; ++i) {
    if (board.advance_substep()) {
      board.latch_tick(TickSamples{.encoder_registers = {encoder_x, 0}, .adc_force_code = 0});
      ++ticks;
    }
  }
  return ticks;
}

TEST(IoBoard, Identification) {
  const IoBoard board = make_board();
  EXPECT_EQ(read(board, regs::kId), regs::kIdValue);
  EXPECT_EQ(read(board, regs::kVersion), regs::kVersionValue);
}

TEST(IoBoard, CounterRunsAt10MHzAndWrapsAt2To32) {
  IoBoard board = make_board(0xFFFF'FF00u);
  EXPECT_EQ(read(board, regs::kClockLive), 0xFFFF'FF00u);
  run(board, 2);
  EXPECT_EQ(read(board, regs::kClockLive), 0xFFFF'FFC8u);
  run(board, 1);
  EXPECT_EQ(read(board, regs::kClockLive), 0x0000'002Cu) << "0xFFFFFF00 + 300 clocks wraps to 44";
  EXPECT_EQ(read(board, regs::kClockAtRead), 0x0000'002Cu);
  EXPECT_EQ(board.elapsed_clocks(), 300u);
}

TEST(IoBoard, TickEvery10000ClocksLatchesSequenceClockAndSamples) {
  IoBoard board = make_board(0xFFFF'0000u);
  EXPECT_EQ(read(board, regs::kTickSequence), 0xFFFF'FFFFu) << "before the first tick";
  EXPECT_EQ(run(board, 99, 7), 0);
  EXPECT_EQ(run(board, 1, 7), 1) << "first tick at 10,000 clocks";
  EXPECT_EQ(read(board, regs::kTickSequence), 0u);
  EXPECT_EQ(read(board, regs::kTickClock), 0xFFFF'0000u + 10'000u);
  EXPECT_EQ(read(board, regs::kEncoderX), 7u);
  run(board, 50, 9);
  EXPECT_EQ(read(board, regs::kEncoderX), 7u) << "snapshot changes only at ticks";
  EXPECT_NE(read(board, regs::kClockAtRead), read(board, regs::kTickClock)) << "CLOCK_AT_READ is live";
  EXPECT_EQ(run(board, 50, 9), 1);
  EXPECT_EQ(read(board, regs::kTickSequence), 1u);
  EXPECT_EQ(read(board, regs::kTickClock), 0xFFFF'0000u + 20'000u);
  EXPECT_EQ(read(board, regs::kEncoderX), 9u);
  EXPECT_EQ(run(board, 1'000), 10) << "ten ticks in 10 ms";
}

TEST(IoBoard, DividerNotAMultipleOfASubstepLatchesAtTheNextBoundary) {
  IoBoard board = make_board();
  ASSERT_TRUE(board.write_register(regs::kTickDivider, 150));
  EXPECT_EQ(read(board, regs::kTickDivider), 150u);
  std::uint32_t latched[4];
  for (std::uint32_t& clock : latched) {
    while (!board.advance_substep()) {
    }
    board.latch_tick({});
    clock = read(board, regs::kTickClock);
  }
  // nominal 150, 300, 450, 600 -> boundaries 200, 300, 500, 600
  EXPECT_EQ(latched[0], 200u);
  EXPECT_EQ(latched[1], 300u);
  EXPECT_EQ(latched[2], 500u);
  EXPECT_EQ(latched[3], 600u);
  EXPECT_FALSE(board.write_register(regs::kTickDivider, 99)) << "faster than one sub-step is refused";
  EXPECT_EQ(read(board, regs::kTickDivider), 150u);
}

TEST(IoBoard, DacCodeMapsToSpeedCommand) {
  IoBoard board = make_board();
  ASSERT_TRUE(board.write_register(regs::kOutputs, regs::kOutputEnableX | regs::kOutputEnableY));
  const double full_mm_s = 1000.0 * 10.0 / 60.0;  // 1000 rpm at 10 V, 10 mm lead
  const double lsb_mm_s = full_mm_s / 2048.0;
  EXPECT_NEAR(lsb_mm_s, 0.08138, 0.5e-5);
  struct Case {
    std::uint32_t code;
    double speed_mm_s;
  };
  for (const Case c : {Case{2048, 0.0}, Case{0, -full_mm_s}, Case{4095, full_mm_s - lsb_mm_s},
                       Case{2049, lsb_mm_s}, Case{1024, -full_mm_s / 2}}) {
    ASSERT_TRUE(board.write_register(regs::kDacX, c.code));
    ASSERT_TRUE(board.write_register(regs::kDacY, c.code));
    EXPECT_NEAR(board.command_mm_s(Axis::x), c.speed_mm_s, 1e-12) << "code " << c.code;
    EXPECT_NEAR(board.command_mm_s(Axis::y), c.speed_mm_s, 1e-12) << "code " << c.code;
    EXPECT_EQ(read(board, regs::kDacX), c.code);
  }
}

TEST(IoBoard, DacCodeAboveFullScaleIsRefused) {
  IoBoard board = make_board();
  ASSERT_TRUE(board.write_register(regs::kDacX, 3000));
  EXPECT_FALSE(board.write_register(regs::kDacX, 4096));
  EXPECT_EQ(read(board, regs::kDacX), 3000u) << "a refused write changes nothing";
}

TEST(IoBoard, DacRegistersStartAtMidScale) {
  const IoBoard board = make_board();
  EXPECT_EQ(read(board, regs::kDacX), 2048u);
  EXPECT_EQ(read(board, regs::kDacY), 2048u);
}

TEST(IoBoard, DisabledAxisGetsZeroCommand) {
  IoBoard board = make_board();
  ASSERT_TRUE(board.write_register(regs::kDacX, 4000));
  ASSERT_TRUE(board.write_register(regs::kDacY, 100));
  EXPECT_EQ(board.command_mm_s(Axis::x), 0.0);
  EXPECT_EQ(board.command_mm_s(Axis::y), 0.0);
  ASSERT_TRUE(board.write_register(regs::kOutputs, regs::kOutputEnableY));
  EXPECT_EQ(board.command_mm_s(Axis::x), 0.0) << "X is still disabled";
  EXPECT_LT(board.command_mm_s(Axis::y), -150.0);
  EXPECT_FALSE(board.write_register(regs::kOutputs, 1u << 5)) << "undefined output bit";
}

TEST(IoBoard, TheSpindleDacAndBitsReachItsDriveOnlyEnabled) {
  IoBoard board = make_board();
  EXPECT_EQ(read(board, regs::kDacSpindle), 2048u) << "reset: 0 V";
  EXPECT_EQ(board.spindle_dac_output_code(), 2048u);
  ASSERT_TRUE(board.write_register(regs::kDacSpindle, 1000));
  EXPECT_FALSE(board.write_register(regs::kDacSpindle, 4096)) << "above the DAC: refused";
  EXPECT_EQ(read(board, regs::kDacSpindle), 1000u) << "and nothing changed";
  EXPECT_EQ(board.spindle_dac_output_code(), 1000u);
  EXPECT_FALSE(board.spindle_enabled());
  ASSERT_TRUE(board.write_register(regs::kOutputs, regs::kOutputSpindleEnable | regs::kOutputSpindleReverse));
  EXPECT_TRUE(board.spindle_enabled());
  EXPECT_TRUE(board.spindle_reverse());
  EXPECT_FALSE(board.enabled(Axis::x)) << "the spindle's bits are not an axis'";
  EXPECT_FALSE(board.write_register(regs::kOutputs, 1u << 10)) << "undefined output bit";
  EXPECT_EQ(read(board, regs::kOutputs), regs::kOutputSpindleEnable | regs::kOutputSpindleReverse);
}

TEST(IoBoard, TheSpindleChannelsAreSnapshotWords) {
  IoBoard board = make_board();
  TickSamples samples;
  samples.spindle_encoder_register = 0xBEEF;
  samples.spindle_index_register = 0x1000 | (3u << regs::kIndexEdgesShift);
  for (int i = 0; i < 99; ++i) ASSERT_FALSE(board.advance_substep());
  EXPECT_EQ(read(board, regs::kSpindleEncoder), 0u);
  ASSERT_TRUE(board.advance_substep());
  board.latch_tick(samples);
  EXPECT_EQ(read(board, regs::kSpindleEncoder), 0xBEEFu);
  EXPECT_EQ(read(board, regs::kSpindleIndex), 0x1000u | (3u << regs::kIndexEdgesShift));
}

class Watchdog : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(board.write_register(regs::kOutputs, regs::kOutputEnableX | regs::kOutputEnableY));
    ASSERT_TRUE(board.write_register(regs::kDacX, 3000));
    ASSERT_TRUE(board.write_register(regs::kDacY, 1000));
    ASSERT_TRUE(board.write_register(regs::kDacSpindle, 3000));
    ASSERT_TRUE(board.write_register(regs::kOutputs, regs::kOutputEnableX | regs::kOutputEnableY |
                                                         regs::kOutputSpindleEnable));
  }
  void kick() { ASSERT_TRUE(board.write_register(regs::kWatchdogKick, regs::kWatchdogKickKey)); }
  IoBoard board = make_board();
};

TEST_F(Watchdog, DisarmedUntilTheFirstKick) {
  run(board, 1'000);  // 10 ms, 3x the timeout
  EXPECT_FALSE(board.watchdog_tripped());
  EXPECT_GT(board.command_mm_s(Axis::x), 0.0);
}

TEST_F(Watchdog, TripsAfterTimeoutAndZeroesOutputs) {
  kick();
  run(board, 300);  // exactly 30,000 clocks: not more than the timeout
  EXPECT_FALSE(board.watchdog_tripped());
  run(board, 1);
  ASSERT_TRUE(board.watchdog_tripped()) << "30,100 clocks without a kick";
  EXPECT_EQ(board.command_mm_s(Axis::x), 0.0);
  EXPECT_EQ(board.command_mm_s(Axis::y), 0.0);
  EXPECT_FALSE(board.enabled(Axis::x));
  EXPECT_EQ(read(board, regs::kDacX), 2048u);
  EXPECT_EQ(read(board, regs::kDacY), 2048u);
  EXPECT_EQ(read(board, regs::kOutputs), 0u) << "every enable, the spindle's too";
  EXPECT_EQ(read(board, regs::kDacSpindle), 2048u);
  EXPECT_EQ(board.spindle_dac_output_code(), 2048u);
  EXPECT_FALSE(board.spindle_enabled());
  run(board, 100);
  EXPECT_NE(read(board, regs::kInputs) & regs::kInputWatchdogTripped, 0u) << "trip visible in the next snapshot";
}

TEST_F(Watchdog, RegularKicksKeepItQuietOtherValuesDoNot) {
  kick();
  for (int i = 0; i < 20; ++i) {
    run(board, 250);
    kick();
  }
  EXPECT_FALSE(board.watchdog_tripped());
  for (int i = 0; i < 4; ++i) {
    run(board, 100);
    ASSERT_TRUE(board.write_register(regs::kWatchdogKick, 0x1234));  // not the key: ignored
  }
  EXPECT_TRUE(board.watchdog_tripped());
}

TEST_F(Watchdog, LatchedUntilControlClear) {
  kick();
  run(board, 301);
  ASSERT_TRUE(board.watchdog_tripped());
  kick();
  ASSERT_TRUE(board.write_register(regs::kOutputs, regs::kOutputEnableX));
  ASSERT_TRUE(board.write_register(regs::kDacX, 3000));
  run(board, 10);
  EXPECT_TRUE(board.watchdog_tripped()) << "a kick does not clear a trip";
  EXPECT_EQ(board.command_mm_s(Axis::x), 0.0) << "outputs stay forced while tripped";
  ASSERT_TRUE(board.write_register(regs::kControl, regs::kControlClearWatchdog));
  EXPECT_FALSE(board.watchdog_tripped());
  EXPECT_GT(board.command_mm_s(Axis::x), 0.0);
  run(board, 1'000);
  EXPECT_FALSE(board.watchdog_tripped()) << "clearing disarms until the next kick";
  run(board, 100);
  EXPECT_EQ(read(board, regs::kInputs) & regs::kInputWatchdogTripped, 0u);
}

TEST(IoBoard, InputsLatchAtTick) {
  IoBoard board = make_board();
  board.set_input(regs::kInputEstop | regs::kInputLimitYNeg | regs::kInputProbe, true);
  board.set_input(regs::kInputWatchdogTripped, true);  // not the bench's bit: ignored
  EXPECT_EQ(read(board, regs::kInputs), 0u);
  run(board, 100);
  EXPECT_EQ(read(board, regs::kInputs), regs::kInputEstop | regs::kInputLimitYNeg | regs::kInputProbe);
  board.set_input(regs::kInputEstop | regs::kInputProbe, false);
  run(board, 100);
  EXPECT_EQ(read(board, regs::kInputs), regs::kInputLimitYNeg);
}

TEST(IoBoard, FaultsAreStickyUntilCleared) {
  IoBoard board = make_board();
  run(board, 100);
  EXPECT_EQ(read(board, regs::kFaults), 0u);
  board.raise_faults(regs::kFaultEncoderY);
  run(board, 100);
  EXPECT_EQ(read(board, regs::kFaults), regs::kFaultEncoderY);
  ASSERT_TRUE(board.write_register(regs::kControl, regs::kControlClearFaults));
  run(board, 100);
  EXPECT_EQ(read(board, regs::kFaults), 0u);
}

TEST(IoBoard, UnmappedAndReadOnlyAccessIsRefused) {
  IoBoard board = make_board();
  std::uint32_t value = 0;
  // The gaps of the 2.0 map, and the slots of the axes the list does not have.
  std::vector<std::uint16_t> unmapped{0x003, 0x00F, 0x024, 0x027, 0x02F, 0x033, 0x100, 0xFFFF};
  for (std::size_t slot = hal::kAxisCount; slot < regs::kMaxAxes; ++slot) {
    const regs::AxisRegisters r = regs::axis_slot(slot);
    unmapped.insert(unmapped.end(), {r.encoder, r.adc_accel, r.index, r.dac});
  }
  for (const std::uint16_t word : unmapped) {
    EXPECT_FALSE(board.read_register(word, value)) << "read of unmapped 0x" << std::hex << word;
    EXPECT_FALSE(board.write_register(word, 1)) << "write to unmapped 0x" << std::hex << word;
  }
  std::vector<std::uint16_t> read_only{regs::kId,      regs::kVersion,     regs::kClockLive,
                                       regs::kTickSequence, regs::kTickClock, regs::kInputs,
                                       regs::kAdcForce, regs::kFaults,      regs::kClockAtRead,
                                       regs::kSpindleEncoder, regs::kSpindleIndex};
  for (const regs::AxisRegisters& r : regs::kAxisRegisters) read_only.insert(read_only.end(), {r.encoder, r.adc_accel, r.index});
  for (const std::uint16_t word : read_only) {
    const std::uint32_t before = read(board, word);
    EXPECT_FALSE(board.write_register(word, 0x5A5A)) << "write to read-only 0x" << std::hex << word;
    if (word != regs::kClockLive && word != regs::kClockAtRead) {
      EXPECT_EQ(read(board, word), before);
    }
  }
  EXPECT_FALSE(board.write_register(regs::kControl, 1u << 7)) << "undefined control bit";
}

TEST(IoBoard, ConfigurationRegistersReadBack) {
  IoBoard board = make_board();
  EXPECT_EQ(read(board, regs::kTickDivider), regs::kDefaultTickDivider);
  EXPECT_EQ(read(board, regs::kWatchdogTimeout), regs::kDefaultWatchdogTimeout);
  ASSERT_TRUE(board.write_register(regs::kWatchdogTimeout, 5'000));
  EXPECT_EQ(read(board, regs::kWatchdogTimeout), 5'000u);
  EXPECT_EQ(read(board, regs::kControl), 0u);
}

}  // namespace
}  // namespace tnv::emu
