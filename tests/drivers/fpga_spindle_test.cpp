// The spindle on the I/O board, end to end at register level: the FPGA
// driver writes DAC_SPINDLE and the OUTPUTS spindle bits over the emulated
// register bus, the emulated machine turns its spindle drive, and the speed
// is read back the way the firmware will read it, from SPINDLE_ENCODER
// counts over the latched tick clock (M-method), with SPINDLE_INDEX.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "drivers/emulated/emulated_register_bus.hpp"
#include "drivers/fpga/fpga_io_board.hpp"
#include "emulator/machine.hpp"
#include "emulator/scenario_file.hpp"
#include "firmware/spindle/spindle_control.hpp"
#include "firmware/spindle/spindle_params.hpp"
#include "hal/io_board_registers.hpp"

namespace tnv::drivers {
namespace {

namespace regs = hal::regs;

constexpr auto kCountsPerRev = static_cast<std::int64_t>(fw::kSpindleEncoderCountsPerRev);

// The 16-bit register's signed step between two snapshots.
std::int64_t wrapped_delta(std::uint32_t now, std::uint32_t before) {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(now - before));
}

class SpindleBench {
 public:
  SpindleBench() {
    EXPECT_TRUE(board.init({}).ok());
    machine.advance_to_next_tick();
    EXPECT_EQ(board.read_inputs(), hal::HalStatus::ok);
    last_raw_ = board.spindle_latched_count();
  }

  // The firmware's outputs for a signed speed: the code and the direction input.
  void command(double rpm, bool enable) {
    board.set_spindle_code(fw::spindle_dac_code(rpm));
    board.set_spindle_reverse(rpm < 0.0);
    board.set_spindle_enable(enable);
  }

  // One firmware tick: outputs (with the kick) out, then the next snapshot in.
  void tick(bool write = true) {
    if (write) {
      board.kick();
      EXPECT_EQ(board.write_outputs(), hal::HalStatus::ok);
    }
    machine.advance_to_next_tick();
    EXPECT_EQ(board.read_inputs(), hal::HalStatus::ok);
    const std::uint32_t raw = board.spindle_latched_count();
    counts_ += wrapped_delta(raw, last_raw_);
    last_raw_ = raw;
  }

  // Mean speed over the next `ticks` ticks, from counts and the latched clock.
  double rpm_over(int ticks) {
    const std::int64_t counts_from = counts_;
    const std::uint32_t clock_from = board.latched_tick().clock_10mhz;
    for (int i = 0; i < ticks; ++i) tick();
    return fw::spindle_rpm(counts_ - counts_from, board.latched_tick().clock_10mhz - clock_from);
  }

  std::int64_t counts() const { return counts_; }
  std::uint32_t raw() const { return last_raw_; }

  emu::Machine machine{*emu::builtin_scenario("no-cut")};
  EmulatedRegisterBus bus{machine};
  FpgaIoBoard board{bus};

 private:
  std::int64_t counts_ = 0;  // extended by signed differences, as the firmware does
  std::uint32_t last_raw_ = 0;
};

// 20 ms windows: one count at each end is 2 / 4096 rev in 20 ms, 1.46 rpm,
// so a difference of two windows' means is good to 2.93 rpm, 146 rpm/s.
constexpr int kWindowTicks = 20;
constexpr double kWindowS = kWindowTicks * 1e-3;
constexpr double kWindowRpm = 2.0 * 60.0 / (4096.0 * kWindowS);

TEST(FpgaSpindle, TurnsOnlyWhenEnabledRampsAtTheDriveLimitAndSettlesWithinOnePercent) {
  SpindleBench b;
  b.command(6000.0, false);  // the speed written, the drive not enabled
  EXPECT_EQ(b.rpm_over(100), 0.0) << "no enable, no rotation";
  EXPECT_TRUE(b.machine.spindle_truth().at_rest);

  b.command(6000.0, true);
  std::vector<double> means;
  for (int w = 0; w < 125; ++w) means.push_back(b.rpm_over(kWindowTicks));  // 2.5 s
  double max_rate = 0.0;
  for (std::size_t i = 1; i < means.size(); ++i) max_rate = std::max(max_rate, (means[i] - means[i - 1]) / kWindowS);
  EXPECT_LE(max_rate, fw::kSpindleDriveAccelRpmS + 2.0 * kWindowRpm / kWindowS) << "the drive's 6,000 rpm/s";
  EXPECT_GE(max_rate, 0.97 * fw::kSpindleDriveAccelRpmS) << "and it does ramp at its limit";
  // 0 -> 99 % of 6000 rpm cannot take less than 5940 / 6000 s.
  const auto first_near = std::find_if(means.begin(), means.end(), [](double n) { return n >= 0.99 * 6000.0; });
  ASSERT_NE(first_near, means.end());
  const auto windows = static_cast<double>(first_near - means.begin() + 1);
  EXPECT_GE(windows * kWindowS, 5940.0 / fw::kSpindleDriveAccelRpmS);
  const double settled = b.rpm_over(100);
  EXPECT_NEAR(settled, 6000.0, 0.01 * 6000.0);
  EXPECT_NEAR(b.machine.spindle_truth().speed_rpm, 6000.0, 0.01 * 6000.0);
  EXPECT_GT(b.counts(), 0) << "forward counts up";
}

TEST(FpgaSpindle, TheDirectionBitReversesAndMustAgreeWithTheCodesSign) {
  SpindleBench b;
  b.command(-3000.0, true);  // code below mid-scale, reverse bit set
  for (int i = 0; i < 2000; ++i) b.tick();
  const std::int64_t before = b.counts();
  EXPECT_NEAR(b.rpm_over(100), -3000.0, 0.01 * 3000.0);
  EXPECT_LT(b.counts(), before) << "reverse counts down";

  // Sign and direction input disagree: the drive is told 0 and comes to rest.
  b.board.set_spindle_code(fw::spindle_dac_code(3000.0));  // reverse bit still set
  for (int i = 0; i < 4000; ++i) b.tick();
  EXPECT_EQ(b.machine.spindle_truth().command_rpm, 0.0);
  EXPECT_EQ(b.rpm_over(100), 0.0);

  // Forward bit with a negative code: it never starts.
  SpindleBench c;
  c.board.set_spindle_code(fw::spindle_dac_code(-3000.0));
  c.board.set_spindle_reverse(false);
  c.board.set_spindle_enable(true);
  EXPECT_EQ(c.rpm_over(200), 0.0);
  EXPECT_TRUE(c.machine.spindle_truth().at_rest);
}

TEST(FpgaSpindle, DisablingBringsItToRestUnderTheSameLawAndItIsThenNotIntegrated) {
  SpindleBench b;
  b.command(6000.0, true);
  for (int i = 0; i < 3000; ++i) b.tick();
  ASSERT_NEAR(b.machine.spindle_truth().speed_rpm, 6000.0, 1.0);
  b.board.set_spindle_enable(false);  // the code stays at 6000 rpm
  // Braking at the limit: 0.5 s takes 3000 rpm off, no more.
  for (int i = 0; i < 500; ++i) b.tick();
  EXPECT_NEAR(b.machine.spindle_truth().speed_rpm, 3000.0, 1.0);
  EXPECT_EQ(b.machine.spindle_truth().command_rpm, 0.0);
  // Then tau_sp: below 1e-3 rpm after 0.8 + 0.2 ln(1.2e6) = 3.6 s in all.
  for (int i = 0; i < 3500; ++i) b.tick();
  const emu::SpindleTruth rest = b.machine.spindle_truth();
  EXPECT_TRUE(rest.at_rest);
  EXPECT_EQ(rest.speed_rpm, 0.0);
  const std::uint32_t raw = b.raw();
  EXPECT_EQ(b.rpm_over(200), 0.0);
  EXPECT_EQ(b.raw(), raw);
  EXPECT_EQ(b.machine.spindle_truth().revolutions, rest.revolutions) << "and stays there";
}

TEST(FpgaSpindle, TheIndexLatchesOncePerRevolutionInEitherDirection) {
  SpindleBench b;
  for (const double rpm : {600.0, -600.0}) {
    b.command(rpm, true);
    for (int i = 0; i < 1500; ++i) b.tick();  // settled: 10 rev/s, 0.01 rev per tick
    std::uint8_t edges = b.board.spindle_index_latch().edges;
    const std::int64_t counts_from = b.counts();
    int edges_seen = 0;
    for (int i = 0; i < 2000; ++i) {
      const std::int64_t before = b.counts();
      b.tick();
      const hal::IndexLatch latch = b.board.spindle_index_latch();
      const auto new_edges = static_cast<std::uint8_t>(latch.edges - edges);
      edges = latch.edges;
      ASSERT_LE(new_edges, 1) << "at most one mark per tick at 10 rev/s";
      if (new_edges == 0) continue;
      ++edges_seen;
      // The count at the edge: a whole revolution (the mark at 0 deg), between
      // the counts of the two snapshots around it.
      const std::int64_t at_edge = b.counts() - wrapped_delta(b.raw(), latch.count);
      EXPECT_EQ(((at_edge % kCountsPerRev) + kCountsPerRev) % kCountsPerRev, 0) << at_edge;
      EXPECT_LE(std::min(before, b.counts()), at_edge);
      EXPECT_GE(std::max(before, b.counts()), at_edge);
    }
    // 2 s at 600 rpm (the DAC's nearest code: 597.66 rpm) is 19.9 revolutions.
    const double revolutions = static_cast<double>(std::llabs(b.counts() - counts_from)) / static_cast<double>(kCountsPerRev);
    EXPECT_GT(revolutions, 19.0);
    EXPECT_LE(std::abs(edges_seen - revolutions), 1.0) << rpm;
  }
}

TEST(FpgaSpindle, AWatchdogTripDropsTheSpindleOutputs) {
  SpindleBench b;
  b.command(3000.0, true);
  for (int i = 0; i < 2000; ++i) b.tick();
  const double running_rpm = b.machine.spindle_truth().speed_rpm;
  ASSERT_NEAR(running_rpm, 3000.0, 1.0);
  for (int i = 0; i < 5; ++i) b.tick(false);  // the firmware stops writing: no kicks, a trip at 3.01 ms
  const emu::BoardOutputs out = b.machine.board_outputs();
  EXPECT_TRUE(out.watchdog_tripped);
  EXPECT_TRUE(out.safe(b.machine.dac_mid_code()));
  EXPECT_FALSE(out.spindle_enabled);
  EXPECT_EQ(out.spindle_dac_register, 2048u);
  std::uint32_t outputs = 0;
  ASSERT_TRUE(b.machine.read_register(regs::kOutputs, outputs));
  EXPECT_EQ(outputs & regs::kOutputSpindleBits, 0u);
  EXPECT_EQ(b.machine.spindle_truth().command_rpm, 0.0);
  // Braking at the limit since the trip (about 2 ms): 6 rpm a millisecond.
  EXPECT_LT(b.machine.spindle_truth().speed_rpm, running_rpm - 6.0);
  EXPECT_GT(b.machine.spindle_truth().speed_rpm, running_rpm - 6000.0 * 5e-3);
}

}  // namespace
}  // namespace tnv::drivers
