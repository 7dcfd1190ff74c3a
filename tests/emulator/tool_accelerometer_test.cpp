// The tool-side accelerometers (ADC_ACCEL_X/Y) through the register door:
// the table's acceleration without a mode, the mode's ringing with one,
// quantised and saturated.
#include "emulator/tool_accelerometer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "emulator/machine.hpp"
#include "hal/io_board_registers.hpp"
#include "tests/emulator/machine_register_read.hpp"

namespace tnv::emu {
namespace {

namespace regs = hal::regs;
using hal::Axis;
using test_support::read;

constexpr double kLsb_mm_s2 = regs::kAccelFullScaleMmS2 / 2048.0;
constexpr std::uint32_t kMid = 2048;

double decode_mm_s2(std::uint32_t code) { return (static_cast<double>(code) - kMid) * kLsb_mm_s2; }

// X without friction (the exponential step response is then exact).
Scenario frictionless_x(double mode_hz, double zeta) {
  Scenario s;
  s.plant[0].coulomb_mm_s = s.plant[0].stiction_mm_s = 0.0;
  s.plant[0].mode_hz = mode_hz;
  s.plant[0].mode_zeta = zeta;
  return s;
}

// Enables both axes with X at `dac_x`; returns ADC_ACCEL_X at the next `ticks` ticks.
std::vector<std::uint32_t> accel_after_step(Machine& m, std::uint32_t dac_x, int ticks) {
  EXPECT_TRUE(m.write_register(regs::kDacX, dac_x));
  EXPECT_TRUE(m.write_register(regs::kDacY, kMid));
  EXPECT_TRUE(m.write_register(regs::kOutputs, regs::kOutputEnableX | regs::kOutputEnableY));
  std::vector<std::uint32_t> codes;
  for (int k = 0; k < ticks; ++k) {
    m.advance_to_next_tick();
    EXPECT_TRUE(m.write_register(regs::kWatchdogKick, regs::kWatchdogKickKey));
    codes.push_back(read(m, regs::kAdcAccelX));
    EXPECT_EQ(read(m, regs::kAdcAccelY), kMid) << "Y holds still: 0 mm/s^2 at tick " << k;
  }
  return codes;
}

TEST(ToolAccelerometer, CodeIsOffsetBinaryQuantisedAndSaturated) {
  EXPECT_EQ(accel_adc_code(0.0), kMid);
  EXPECT_EQ(accel_adc_code(regs::kAccelFullScaleMmS2 / 2.0), 3072u);
  EXPECT_EQ(accel_adc_code(-regs::kAccelFullScaleMmS2 / 2.0), 1024u);
  EXPECT_EQ(accel_adc_code(0.49 * kLsb_mm_s2), kMid) << "rounds to the nearest LSB";
  EXPECT_EQ(accel_adc_code(0.51 * kLsb_mm_s2), kMid + 1);
  EXPECT_EQ(accel_adc_code(1e9), 4095u);
  EXPECT_EQ(accel_adc_code(-1e9), 0u);
  EXPECT_EQ(accel_adc_code(std::nan("")), 0u);
}

TEST(ToolAccelerometer, WithoutAModeItReadsTheTableAccelerationAndNoRinging) {
  const Scenario s = frictionless_x(0.0, 0.0);
  Machine m(s);
  EXPECT_EQ(read(m, regs::kAdcAccelX), kMid) << "at rest before the first tick";
  const std::uint32_t step_codes = 123;  // 10.0 mm/s
  const double u_mm_s = step_codes * (1000.0 * 10.0 / 60.0) / 2048.0;
  const std::vector<std::uint32_t> codes = accel_after_step(m, kMid + step_codes, 200);
  const double tau = s.plant[0].tau_s;
  for (std::size_t k = 0; k < codes.size(); ++k) {
    // tau dv/dt = K u - v from rest: a(t) = K u / tau e^{-t/tau}
    const double t = static_cast<double>(k + 1) * 1e-3;
    const double expected_mm_s2 = s.plant[0].gain * u_mm_s / tau * std::exp(-t / tau);
    EXPECT_NEAR(decode_mm_s2(codes[k]), expected_mm_s2, 0.5 * kLsb_mm_s2 + 1e-9) << "mm/s^2 at t = " << t << " s";
  }
  EXPECT_GT(decode_mm_s2(codes[0]), 100.0 * kLsb_mm_s2) << "a 10 mm/s step on a 5 ms axis is well resolved";
  for (std::size_t k = 60; k < codes.size(); ++k) EXPECT_EQ(codes[k], kMid) << "no ringing at tick " << k;
}

TEST(ToolAccelerometer, AModeRingsAtItsFrequencyAfterAStep) {
  const double mode_hz = 47.0, zeta = 0.02;
  Machine m(frictionless_x(mode_hz, zeta));
  const std::vector<std::uint32_t> codes = accel_after_step(m, kMid + 123, 400);
  // After the table transient (10 tau = 54 ms) only the ring is left:
  // count sign changes about mid-scale and measure the period.
  std::vector<double> crossings_s;
  double peak_mm_s2 = 0.0;
  std::size_t last = 60;  // last sample off mid-scale (a sample exactly at 0 belongs to neither side)
  for (std::size_t k = 61; k < codes.size(); ++k) {
    const double a0 = decode_mm_s2(codes[last]), a1 = decode_mm_s2(codes[k]);
    peak_mm_s2 = std::max(peak_mm_s2, std::fabs(a1));
    if (a1 == 0.0) continue;
    if (a0 != 0.0 && (a0 < 0.0) != (a1 < 0.0)) {
      const double span_s = static_cast<double>(k - last) * 1e-3;
      crossings_s.push_back(static_cast<double>(k) * 1e-3 - a1 / (a1 - a0) * span_s);  // linear interpolation
    }
    last = k;
  }
  ASSERT_GE(crossings_s.size(), 20u) << "the tool point keeps ringing";
  const double half_periods = static_cast<double>(crossings_s.size() - 1);
  const double ring_hz = half_periods / (2.0 * (crossings_s.back() - crossings_s.front()));
  const double damped_hz = mode_hz * std::sqrt(1.0 - zeta * zeta);
  EXPECT_NEAR(ring_hz, damped_hz, 0.01 * damped_hz) << "ringing frequency (Hz)";
  EXPECT_GT(peak_mm_s2, 50.0 * kLsb_mm_s2) << "ring amplitude (mm/s^2)";
}

TEST(ToolAccelerometer, SaturatesAtFullScale) {
  Machine up(frictionless_x(0.0, 0.0));
  // Full-scale DAC: 166.7 mm/s on a 5.36 ms axis is 3.1e4 mm/s^2 at the step, beyond +-2 g.
  EXPECT_EQ(accel_after_step(up, 4095, 1).front(), 4095u);
  Machine down(frictionless_x(0.0, 0.0));
  EXPECT_EQ(accel_after_step(down, 0, 1).front(), 0u);
}

}  // namespace
}  // namespace tnv::emu
