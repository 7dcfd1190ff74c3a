// [io]: the tick's output write lands read latency + work + write latency
// after the latch, measured on the emulated board sub-step by sub-step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "emulator/machine.hpp"
#include "hal/io_board_registers.hpp"
#include "tests/emulator/machine_register_read.hpp"

namespace tnv::emu {
namespace {

namespace regs = hal::regs;
using hal::Axis;
using test_support::read;

Scenario with_io(double read_us, double write_us, double jitter_us = 0.0) {
  Scenario s;
  s.io = IoParams{.read_latency_us = read_us, .write_latency_us = write_us, .jitter_us = jitter_us};
  return s;
}

// Writes a new X code just after a latch, as the firmware's tick does, and
// steps 10 us at a time: the microseconds from the latch to the start of the
// first sub-step that runs with the new command.
std::optional<int> landing_us(Machine& m, std::uint32_t code, std::optional<double> work_ns = std::nullopt) {
  const std::uint64_t latch = m.elapsed_clocks();
  EXPECT_TRUE(m.write_register(regs::kDacX, code));
  EXPECT_TRUE(m.write_register(regs::kOutputs, regs::kOutputEnableX));
  if (work_ns) m.set_firmware_work_ns(*work_ns);
  const double u_new = (static_cast<double>(code) - m.dac_mid_code()) * 1000.0 * 10.0 / 60.0 / 2048.0;
  for (int k = 0; k < 99; ++k) {
    m.advance_clocks(100);
    if (std::abs(m.truth(Axis::x).command_mm_s - u_new) < 1e-9) return static_cast<int>((m.elapsed_clocks() - latch) / 10) - 10;
  }
  return std::nullopt;
}

TEST(OutputTransport, WriteLandsReadPlusWriteLatencyAfterTheLatch) {
  Machine m(with_io(100.0, 50.0));
  m.advance_to_next_tick();
  const std::uint64_t latch = m.elapsed_clocks();
  EXPECT_EQ(read(m, regs::kClockAtRead) - read(m, regs::kTickClock), 1000u) << "the read completes 100 us after the latch";
  const std::uint32_t code = m.dac_mid_code() + 500;
  ASSERT_TRUE(m.write_register(regs::kDacX, code));
  ASSERT_TRUE(m.write_register(regs::kOutputs, regs::kOutputEnableX));
  EXPECT_EQ(read(m, regs::kDacX), code) << "a read after the write sees it (the link keeps order)";
  EXPECT_EQ(m.board_outputs().dac_output[0], m.dac_mid_code()) << "but the DAC has not got it yet";
  EXPECT_FALSE(m.board_outputs().enabled[0]);
  for (int k = 1; k <= 20; ++k) {
    m.advance_clocks(100);
    const bool landed = m.board_outputs().dac_output[0] == code && m.board_outputs().enabled[0];
    EXPECT_EQ(landed, k >= 15) << (m.elapsed_clocks() - latch) / 10 << " us after the latch";
  }
}

TEST(OutputTransport, FirmwareWorkAddsToTheLanding) {
  Machine m(with_io(100.0, 50.0));
  m.advance_to_next_tick();
  EXPECT_EQ(landing_us(m, m.dac_mid_code() + 300), 150);
  m.advance_to_next_tick();
  EXPECT_EQ(landing_us(m, m.dac_mid_code() + 301, 25'000.0), 180) << "150 us + 25 us of work, on the 10 us grid";
  m.advance_to_next_tick();
  EXPECT_EQ(landing_us(m, m.dac_mid_code() + 302), 150) << "the work counts once, for its own tick";
}

TEST(OutputTransport, WithoutIoTheWriteLandsAtOnce) {
  Machine m(Scenario{});
  m.advance_to_next_tick();
  ASSERT_TRUE(m.write_register(regs::kDacX, m.dac_mid_code() + 500));
  ASSERT_TRUE(m.write_register(regs::kOutputs, regs::kOutputEnableX));
  EXPECT_EQ(m.board_outputs().dac_output[0], m.dac_mid_code() + 500);
  EXPECT_EQ(read(m, regs::kClockAtRead), read(m, regs::kTickClock));
  m.advance_to_next_tick();
  EXPECT_EQ(landing_us(m, m.dac_mid_code() + 700, 25'000.0), 0) << "no transport: the work does not delay";
}

TEST(OutputTransport, JitterIsUniformPerTransferAndSeeded) {
  const auto landings = [](std::uint32_t seed) {
    Scenario s = with_io(0.0, 0.0, 100.0);
    s.noise.seed = seed;
    Machine m(s);
    std::vector<int> out;
    for (int k = 0; k < 400; ++k) {
      m.advance_to_next_tick();
      const std::uint32_t read_delay = read(m, regs::kClockAtRead) - read(m, regs::kTickClock);
      EXPECT_LE(read_delay, 1000u) << "read jitter within 0..100 us";
      out.push_back(landing_us(m, m.dac_mid_code() + 100 + static_cast<std::uint32_t>(k % 2)).value_or(-1));
    }
    return out;
  };
  const std::vector<int> a = landings(1);
  double sum = 0.0;
  int lo = 1000, hi = -1;
  for (int us : a) {
    sum += us;
    lo = std::min(lo, us);
    hi = std::max(hi, us);
  }
  // Read and write jitter, each U[0, 100 us]: the landing is their sum rounded up to 10 us.
  EXPECT_GE(lo, 0);
  EXPECT_LE(hi, 200);
  EXPECT_NEAR(sum / static_cast<double>(a.size()), 105.0, 8.0) << "mean landing, 100 us + half a sub-step of rounding";
  EXPECT_GT(hi - lo, 120) << "the landing moves from tick to tick";
  EXPECT_EQ(a, landings(1)) << "same seed, same jitter";
  EXPECT_NE(a, landings(2));
}

}  // namespace
}  // namespace tnv::emu
