// Issue 7, "a structural mode if present" and "the input shaper for the
// identified mode": the firmware's excitation steps read through the
// tool-side accelerometer, fitted on the host (tools/hil/tune_mode.hpp),
// against each scenario's true mode; then the ZVD shaper designed from the
// identified mode on a HIL move, scored at the tool point.
//
// Tables: the built-in flex-30 and flex-100 (X), and two made up for this
// test and never used while writing the fit (mode-47: X 47 Hz / zeta 0.035 on
// tau 9 ms, Y 163 Hz / zeta 0.01 on tau 4 ms). The reference plant has no mode.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "emulator/scenario_file.hpp"
#include "firmware/shaper/residual_vibration.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "hal/io_board_registers.hpp"
#include "tools/hil/shaper_move_run.hpp"
#include "tools/hil/tune_design.hpp"
#include "tools/hil/tune_identify.hpp"
#include "tools/hil/tune_mode.hpp"

namespace tnv::hil {
namespace {

// mode-47: different tau, K, friction and a mode on each axis.
emu::Scenario made_up_mode47_table() {
  emu::Scenario s = *emu::builtin_scenario("no-cut");
  s.name = "mode-47";
  s.plant[0].tau_s = 0.0090;
  s.plant[0].gain = 0.9;
  s.plant[0].coulomb_mm_s = 2.0;
  s.plant[0].stiction_mm_s = 3.2;
  s.plant[0].mode_hz = 47.0;
  s.plant[0].mode_zeta = 0.035;
  s.plant[1].tau_s = 0.0040;
  s.plant[1].gain = 1.1;
  s.plant[1].coulomb_mm_s = 0.8;
  s.plant[1].stiction_mm_s = 1.5;
  s.plant[1].mode_hz = 163.0;
  s.plant[1].mode_zeta = 0.01;
  return s;
}

std::string mode_where(const emu::Scenario& s, hal::Axis axis) {
  return s.name + " axis " + hal::axis_name(axis);
}

void expect_mode_identified(const emu::Scenario& s, hal::Axis axis) {
  const emu::AxisPlantParams& truth = s.plant[hal::index(axis)];
  const AxisIdentification id = identify_axis_on_emulator(s, axis);
  const std::string where = mode_where(s, axis);
  ASSERT_TRUE(id.ok) << where << ": " << id.error;
  ASSERT_TRUE(id.mode_found) << where << ": no mode found (" << id.mode_fit.note << "), true " << truth.mode_hz
                             << " Hz";
  EXPECT_NEAR(id.mode_hz, truth.mode_hz, 0.03 * truth.mode_hz)
      << where << ": mode " << id.mode_hz << " Hz, true " << truth.mode_hz << " Hz";
  EXPECT_NEAR(id.mode_zeta, truth.mode_zeta, 0.3 * truth.mode_zeta)
      << where << ": damping ratio " << id.mode_zeta << ", true " << truth.mode_zeta;
  const AxisDesign d = design_axis(id);
  ASSERT_TRUE(d.shaper.enabled) << where << ": " << d.shaper.note;
  EXPECT_EQ(d.shaper.spec.type, fw::ShaperType::zvd) << where;
  EXPECT_EQ(d.shaper.spec.mode.freq_hz, id.mode_hz) << where;
}

// Each identification is about 2 simulated seconds.
TEST(StructuralModeIdentify, FindsTheModeWithin3PercentOnFourAxes) {
  expect_mode_identified(*emu::builtin_scenario("flex-30"), hal::Axis::x);
  expect_mode_identified(*emu::builtin_scenario("flex-100"), hal::Axis::x);
  const emu::Scenario made_up = made_up_mode47_table();
  expect_mode_identified(made_up, hal::Axis::x);
  expect_mode_identified(made_up, hal::Axis::y);
}

TEST(StructuralModeIdentify, ReportsNoModeOnTheReferencePlant) {
  const emu::Scenario reference = *emu::builtin_scenario("no-cut");
  for (const hal::Axis axis : {hal::Axis::x, hal::Axis::y}) {
    const AxisIdentification id = identify_axis_on_emulator(reference, axis);
    const std::string where = mode_where(reference, axis);
    ASSERT_TRUE(id.ok) << where << ": " << id.error;
    ASSERT_GT(id.mode_fit.samples, 1000) << where << ": the accelerometer was read";
    EXPECT_FALSE(id.mode_found) << where << ": found " << id.mode_hz << " Hz, zeta " << id.mode_zeta
                                << " where the table has no mode";
    EXPECT_LT(id.mode_fit.explained_share, kMinExplainedShare) << where;
    const AxisDesign d = design_axis(id);
    EXPECT_FALSE(d.shaper.enabled) << where << ": no mode, no shaper";
  }
}

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

// Identify, design, then the same move unshaped and with the designed
// shaper: the tool point's residual vibration after the move.
void expect_shaper_reduces_residual(const emu::Scenario& s, hal::Axis axis, double max_ratio) {
  const std::string where = mode_where(s, axis);
  const AxisIdentification id = identify_axis_on_emulator(s, axis);
  ASSERT_TRUE(id.ok && id.mode_found) << where << ": " << id.error << id.mode_fit.note;
  const AxisDesign d = design_axis(id);
  ASSERT_TRUE(d.shaper.enabled) << where << ": " << d.shaper.note;
  MoveRunRequest request;
  request.scenario = s;
  request.move = {axis, 10.0, 100.0, 0.02, 0.0};
  request.window_s = 1.0;
  const MoveRunResult unshaped = run_move(request, fw::default_firmware_config());
  request.shaper = d.shaper.spec;
  const MoveRunResult shaped = run_move(request, fw::default_firmware_config());
  // The same rule at the true mode: what a perfect identification would give.
  const emu::AxisPlantParams& truth = s.plant[hal::index(axis)];
  request.shaper = fw::ShaperSpec{fw::ShaperType::zvd, {truth.mode_hz, truth.mode_zeta}, {0.0, 0.0}};
  const MoveRunResult ideal = run_move(request, fw::default_firmware_config());
  ASSERT_TRUE(unshaped.completed) << where << ": " << unshaped.error;
  ASSERT_TRUE(shaped.completed) << where << ": " << shaped.error;
  ASSERT_GT(unshaped.residual_pp_um, 20.0) << where << ": the unshaped move must ring the mode (um p-p)";
  EXPECT_LT(shaped.residual_pp_um, max_ratio * unshaped.residual_pp_um)
      << where << ": tool residual " << shaped.residual_pp_um << " um p-p with the designed ZVD at " << id.mode_hz
      << " Hz vs " << unshaped.residual_pp_um << " um unshaped";
  ASSERT_TRUE(ideal.completed) << where << ": " << ideal.error;
  // Single runs differ by a few um from the standstill stick-slip (shaper_move_compare.hpp):
  // the identification may cost at most 5 % of the unshaped residual.
  EXPECT_LE(shaped.residual_pp_um, ideal.residual_pp_um + 0.05 * unshaped.residual_pp_um)
      << where << ": identified-mode ZVD leaves " << shaped.residual_pp_um << " um p-p, true-mode ZVD "
      << ideal.residual_pp_um << " um";
  ::testing::Test::RecordProperty(s.name + "_" + hal::axis_name(axis) + "_residual_um", std::to_string(unshaped.residual_pp_um) + " -> " +
                                                                         std::to_string(shaped.residual_pp_um) + " (true-mode ZVD " +
                                                                         std::to_string(ideal.residual_pp_um) + ")");
}

TEST(StructuralModeShaper, DesignedShaperCutsTheToolResidual) {
  expect_shaper_reduces_residual(*emu::builtin_scenario("flex-30"), hal::Axis::x, 0.1);
  expect_shaper_reduces_residual(made_up_mode47_table(), hal::Axis::x, 0.1);
}

}  // namespace
}  // namespace tnv::hil

namespace tnv::hil {
namespace {

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
}  // namespace tnv::hil
