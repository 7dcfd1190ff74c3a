// The mode fit and the shaper rule without a table (tools/tune/mode_fit.hpp,
// shaper_choice.hpp): synthetic accelerometer windows, and why the rule
// picks ZVD. The fit on the emulated tables is
// tests/hil/structural_mode_identify_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "firmware/shaper/residual_vibration.hpp"
#include "hal/io_board_registers.hpp"
#include "tools/tune/mode_fit.hpp"
#include "tools/tune/shaper_choice.hpp"

namespace tnv::tune {
namespace {

// The rule's reason: at the fit's 3 % tolerance ZVD leaves well under 1 %
// of the vibration, ZV several times more.
TEST(StructuralModeShaperRule, ZvdToleratesA3PercentFrequencyError) {
  const fw::ModeSpec mode{30.0, 0.02};
  const fw::ImpulseTrain zvd = fw::design_impulses(fw::ShaperType::zvd, mode);
  const fw::ImpulseTrain zv = fw::design_impulses(fw::ShaperType::zv, mode);
  for (const double ratio : {0.97, 1.03}) {
    EXPECT_LT(fw::residual_vibration(zvd, 30.0 * ratio, 0.02), 0.01) << "ZVD at " << ratio << " x the design frequency";
    EXPECT_GT(fw::residual_vibration(zv, 30.0 * ratio, 0.02), 0.03) << "ZV at " << ratio << " x the design frequency";
  }
  EXPECT_FALSE(shaper_for_mode(false, 30.0, 0.02).enabled);
  EXPECT_FALSE(shaper_for_mode(true, 300.0, 0.02).enabled) << "above the shaper's 200 Hz range";
}

// fit_mode alone on synthetic windows: exact ringing plus a table transient,
// quantised like the accelerometer; clipped at full scale.
std::vector<AccelWindow> synthetic_mode_windows(double f_hz, double zeta, double ring_mm_s2, double clip_mm_s2) {
  const double lsb = hal::regs::kAccelFullScaleMmS2 / 2048.0;
  const double w = 2.0 * 3.141592653589793 * f_hz, wd = w * std::sqrt(1.0 - zeta * zeta);
  std::vector<AccelWindow> out;
  for (const double sign : {1.0, -1.0}) {
    AccelWindow win;
    win.table_tau_s = 0.006;
    for (int j = 0; j < 200; ++j) {
      const double t = j * 1e-3;
      double a = sign * (1500.0 * std::exp(-t / 0.006) + ring_mm_s2 * std::exp(-zeta * w * t) * std::cos(wd * t + 0.3));
      a = std::clamp(a, -clip_mm_s2, clip_mm_s2);
      win.accel_mm_s2.push_back(std::round(a / lsb) * lsb);
    }
    out.push_back(win);
  }
  return out;
}

TEST(StructuralModeFit, SyntheticRingFoundAndAbsentRingNot) {
  const double lsb = hal::regs::kAccelFullScaleMmS2 / 2048.0;
  const ModeFit found = fit_mode(synthetic_mode_windows(58.0, 0.025, 800.0, 1e9), 1e-3, lsb);
  ASSERT_TRUE(found.found) << found.note;
  EXPECT_NEAR(found.freq_hz, 58.0, 0.3) << "Hz";
  EXPECT_NEAR(found.zeta, 0.025, 0.0025);
  const ModeFit none = fit_mode(synthetic_mode_windows(58.0, 0.025, 0.0, 1e9), 1e-3, lsb);
  EXPECT_FALSE(none.found) << "pure table transient: found " << none.freq_hz << " Hz";
  // A ring that saturates the ADC at first: the clipped samples are left out.
  const double full_scale = 2047.0 * lsb;
  const ModeFit clipped = fit_mode(synthetic_mode_windows(58.0, 0.025, 30000.0, full_scale), 1e-3, lsb);
  ASSERT_TRUE(clipped.found) << clipped.note;
  EXPECT_NEAR(clipped.freq_hz, 58.0, 0.3) << "Hz, with the first peaks clipped at full scale";
}

}  // namespace
}  // namespace tnv::tune
