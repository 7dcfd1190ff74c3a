// [noise]: the ADC noise is as large as set, the DAC's offset and gain land
// on the command, encoder glitches are miscounts the decoder keeps, and
// one seed gives one run, bit for bit.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "emulator/machine.hpp"
#include "emulator/noise_stream.hpp"
#include "hal/io_board_registers.hpp"
#include "tests/emulator/machine_register_read.hpp"

namespace tnv::emu {
namespace {

namespace regs = hal::regs;
using hal::Axis;
using test_support::read;

constexpr int kTicks = 20'000;
constexpr double kG_mm_s2 = 9806.65;

TEST(NoiseStream, SameSeedSameNumbersAndAStandardNormal) {
  NoiseStream a(42, 1), b(42, 1), other(42, 2);
  double sum = 0.0, sum_sq = 0.0;
  bool differs = false;
  constexpr int kN = 200'000;
  for (int i = 0; i < kN; ++i) {
    const double x = a.normal();
    ASSERT_EQ(x, b.normal());
    differs = differs || x != other.normal();
    sum += x;
    sum_sq += x * x;
  }
  EXPECT_TRUE(differs) << "another stream number gives other numbers";
  EXPECT_NEAR(sum / kN, 0.0, 0.01);
  EXPECT_NEAR(std::sqrt(sum_sq / kN), 1.0, 0.01);
}

TEST(SensorNoise, ForceAdcNoiseHasTheSetRms) {
  Scenario s;
  s.noise.force_adc_v_rms = 0.05;
  s.noise.seed = 7;
  Machine m(s);
  // At rest the force is 0 V: the unipolar ADC reads the positive half of
  // the noise and 0 below, so E[v^2] = sigma^2 / 2 and half the codes are 0.
  double sum_sq_v2 = 0.0;
  int zeros = 0;
  for (int k = 0; k < kTicks; ++k) {
    m.advance_to_next_tick();
    const double volts = read(m, regs::kAdcForce) * 10.0 / 4095.0;
    sum_sq_v2 += volts * volts;
    zeros += volts == 0.0 ? 1 : 0;
  }
  const double rms_v = std::sqrt(2.0 * sum_sq_v2 / kTicks);
  EXPECT_NEAR(rms_v, 0.05, 0.05 * 0.03) << "force ADC noise " << rms_v * 1e3 << " mV rms, set 50 mV";
  EXPECT_NEAR(static_cast<double>(zeros) / kTicks, 0.5, 0.02);
}

TEST(SensorNoise, AccelerometerNoiseAndBiasAsSet) {
  Scenario s;
  s.noise.accel_g_rms = 0.02;
  s.noise.accel_bias_g = 0.05;
  s.noise.seed = 3;
  Machine m(s);
  std::array<double, 2> sum{}, sum_sq{};
  for (int k = 0; k < kTicks; ++k) {
    m.advance_to_next_tick();
    for (std::size_t i = 0; i < 2; ++i) {
      const std::uint32_t code = read(m, i == 0 ? regs::kAdcAccelX : regs::kAdcAccelY);
      const double g = (static_cast<double>(code) - 2048.0) / 2048.0 * regs::kAccelFullScaleMmS2 / kG_mm_s2;
      sum[i] += g;
      sum_sq[i] += g * g;
    }
  }
  for (std::size_t i = 0; i < 2; ++i) {
    const double mean_g = sum[i] / kTicks;
    const double rms_g = std::sqrt(sum_sq[i] / kTicks - mean_g * mean_g);
    EXPECT_NEAR(mean_g, 0.05, 0.001) << "axis " << i << ": bias " << mean_g * 1e3 << " mg, set 50 mg";
    EXPECT_NEAR(rms_g, 0.02, 0.02 * 0.03) << "axis " << i << ": noise " << rms_g * 1e3 << " mg rms, set 20 mg";
  }
}

TEST(SensorNoise, DacOffsetAndGainErrorReachTheServopack) {
  Scenario s;
  s.noise.dac_offset_v = 0.01;
  s.noise.dac_gain_error = 0.003;
  Machine m(s);
  ASSERT_TRUE(m.write_register(regs::kDacX, m.dac_mid_code() + 1000));
  ASSERT_TRUE(m.write_register(regs::kDacY, m.dac_mid_code()));
  ASSERT_TRUE(m.write_register(regs::kOutputs, regs::kOutputEnableX | regs::kOutputEnableY));
  m.advance_clocks(100);
  // 1000 rpm at 10 V and a 10 mm lead: 100 rpm/V, 1 V = 16.667 mm/s.
  const double lsb_mm_s = 1000.0 * 10.0 / 60.0 / 2048.0;
  const double offset_mm_s = 0.01 * 100.0 * 10.0 / 60.0;
  EXPECT_NEAR(m.truth(Axis::x).command_mm_s, 1000.0 * lsb_mm_s * 1.003 + offset_mm_s, 1e-12);
  EXPECT_NEAR(m.truth(Axis::y).command_mm_s, offset_mm_s, 1e-15) << "mid-scale still puts out the offset";
  ASSERT_TRUE(m.write_register(regs::kOutputs, 0));
  m.advance_clocks(100);
  EXPECT_EQ(m.truth(Axis::y).command_mm_s, 0.0) << "a disabled drive ignores its input";
}

// Each glitch is one step of +-counts in the register that stays: one
// change per glitch (a transient miscount would show as two, there and back).
TEST(SensorNoise, EncoderGlitchesArePoissonMiscountsTheDecoderKeeps) {
  Scenario s;
  s.noise.encoder_glitch_per_s = 50.0;
  s.noise.encoder_glitch_counts = 3;
  s.noise.seed = 11;
  Machine m(s);  // at rest, servo off: every change of the register is a glitch
  std::array<std::uint32_t, 2> last{read(m, regs::kEncoderX), read(m, regs::kEncoderY)};
  std::array<int, 2> changes{}, net_counts{};
  for (int k = 0; k < kTicks; ++k) {
    m.advance_to_next_tick();
    for (std::size_t i = 0; i < 2; ++i) {
      const std::uint32_t now = read(m, i == 0 ? regs::kEncoderX : regs::kEncoderY);
      const auto step = static_cast<std::int16_t>(static_cast<std::uint16_t>(now - last[i]));
      last[i] = now;
      if (step == 0) continue;
      ++changes[i];
      net_counts[i] += step;
      EXPECT_EQ(step % 3, 0) << "a step of " << step << " counts, glitches are 3";
    }
  }
  for (std::size_t i = 0; i < 2; ++i) {
    // 20 s at 50/s: 1000 expected, Poisson sigma 32; two in one tick (p ~ 0.1 %) show as one change.
    EXPECT_NEAR(changes[i], 1000, 130) << "axis " << i;
    EXPECT_EQ(m.truth(hal::axis_from_index(i)).motor_position_mm, i == 0 ? 6.0 : 0.0) << "the table never moved";
    const std::int64_t true_count = i == 0 ? 14'400 : 0;
    EXPECT_EQ(static_cast<std::int16_t>(static_cast<std::uint16_t>(last[i] - static_cast<std::uint32_t>(true_count))),
              net_counts[i])
        << "axis " << i << ": the register is off by every glitch so far";
  }
}

Scenario everything_on(std::uint32_t seed) {
  Scenario s;
  s.noise = NoiseParams{.seed = seed, .force_adc_v_rms = 0.01, .accel_g_rms = 0.01, .accel_bias_g = 0.01,
                        .dac_offset_v = 0.005, .dac_gain_error = 0.002, .encoder_glitch_per_s = 20.0,
                        .encoder_glitch_counts = 1};
  s.io = IoParams{.read_latency_us = 80.0, .write_latency_us = 40.0, .jitter_us = 60.0};
  for (AxisPlantParams& p : s.plant) {
    p.backlash_um = 8.0;
    p.lead_error_um_per_m = 50.0;
    p.pitch_error_um = 2.0;
    p.accel_limit_mm_s2 = 3000.0;
  }
  return s;
}

// Every snapshot word and the table truth, tick by tick, under a commanded motion.
std::vector<std::uint64_t> record_run(const Scenario& s) {
  Machine m(s);
  std::vector<std::uint64_t> out;
  const std::uint32_t mid = m.dac_mid_code();
  for (int k = 0; k < 3000; ++k) {
    m.advance_to_next_tick();
    for (std::uint16_t w = regs::kSnapshotFirst; w < regs::kSnapshotFirst + regs::kSnapshotWords; ++w) out.push_back(read(m, w));
    for (Axis a : {Axis::x, Axis::y}) {
      out.push_back(std::bit_cast<std::uint64_t>(m.truth(a).position_mm));
    }
    const auto swing = static_cast<std::uint32_t>(400.0 + 300.0 * std::sin(k * 0.01));
    EXPECT_TRUE(m.write_register(regs::kDacX, (k / 500) % 2 == 0 ? mid + swing : mid - swing));
    EXPECT_TRUE(m.write_register(regs::kDacY, mid + swing / 2));
    EXPECT_TRUE(m.write_register(regs::kOutputs, regs::kOutputEnableX | regs::kOutputEnableY));
  }
  return out;
}

TEST(SensorNoise, SameSeedSameRunBitForBitAnotherSeedAnotherRun) {
  const std::vector<std::uint64_t> first = record_run(everything_on(5));
  const std::vector<std::uint64_t> again = record_run(everything_on(5));
  const std::vector<std::uint64_t> other = record_run(everything_on(6));
  EXPECT_TRUE(first == again) << "seed 5 twice gave two runs";
  EXPECT_FALSE(first == other) << "seeds 5 and 6 gave the same run";
}

}  // namespace
}  // namespace tnv::emu
