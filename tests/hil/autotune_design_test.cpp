// The gains designed from an identified table satisfy the
// papers' conditions (Theorem 2: phi > eta/(q+1); Theorem 5: 0 < gamma <
// min(1-g, q)) and give a stable linearised loop on the identified model
// and on the true one, on tables other than the reference plant.
#include <gtest/gtest.h>

#include "emulator/scenario_file.hpp"
#include "firmware/control/linear_controller.hpp"
#include "firmware/control/loop_analysis.hpp"
#include "tests/sanitized_build.hpp"
#include "tools/hil/tune_identify.hpp"
#include "tools/tune/axis_design.hpp"

namespace tnv::hil {
namespace {

using namespace tnv::tune;

void expect_sound_design(const char* name, double tau_s, double gain, double fc, double fs) {
  emu::Scenario s = *emu::builtin_scenario("no-cut");
  s.plant[0].tau_s = tau_s;
  s.plant[0].gain = gain;
  s.plant[0].coulomb_mm_s = fc;
  s.plant[0].stiction_mm_s = fs;
  const AxisIdentification id = identify_axis_on_emulator(s, hal::Axis::x);
  ASSERT_TRUE(id.ok) << name << ": " << id.error;
  const AxisDesign d = design_axis(id);
  ASSERT_TRUE(d.ok) << name << ": " << d.error;
  const fw::SlidingModeParams& p = d.sliding;
  EXPECT_GT(p.phi_mm_s, p.eta_mm_s / (p.q + 1.0)) << name << ": Theorem 2, phi " << p.phi_mm_s << " mm/s";
  EXPECT_GT(p.gamma, 0.0) << name;
  EXPECT_LT(p.gamma, std::min(1.0 - p.g, p.q)) << name << ": Theorem 5, gamma " << p.gamma;
  EXPECT_GT(p.q, 0.0);
  EXPECT_LT(p.q, 1.0);
  EXPECT_GT(p.g, 0.0);
  EXPECT_LT(p.g, 1.0);
  EXPECT_LT(d.rdvsc_spectral_radius, 1.0) << name << ": R-DVSC+DDC on the identified model";
  EXPECT_LT(d.pid_spectral_radius, 1.0) << name << ": PID on the identified model";
  const fw::AxisModel truth = fw::zoh_axis_model(tau_s, gain, 1e-3);
  EXPECT_LT(sliding_loop_spectral_radius(truth, p), 1.0) << name << ": R-DVSC+DDC on the true model";
  fw::SlidingModeParams dvsc = p;
  dvsc.gamma = 0.0;
  EXPECT_LT(sliding_loop_spectral_radius(truth, dvsc), 1.0) << name << ": DVSC+DDC on the true model";
  const fw::LinearController pid = fw::linear_pid(truth, d.pid.kp, d.pid.ki, d.pid.kd, d.pid.derivative_filter_tf_s);
  EXPECT_LT(fw::spectral_radius(fw::closed_loop_poles(truth, pid)), 1.0) << name << ": PID on the true model";
  // The whole designed config passes the firmware's own validation.
  const fw::FirmwareConfig config = apply_designs(fw::default_firmware_config(), d, d);
  const fw::ConfigError e = fw::validate(config);
  EXPECT_TRUE(e.ok()) << name << ": " << e.section << ": " << e.field << ": " << e.reason;
}

TEST(AutotuneDesign, TheoremConditionsAndStableLoopsOnThreeTables) {
  // Each table is judged alone: a sanitizer build designs for the reference X only.
  if (!tnv::test::kSanitizedBuild) {
    expect_sound_design("slow-heavy", 0.0120, 0.85, 2.5, 4.0);
    expect_sound_design("fast-light", 0.0030, 1.20, 0.6, 1.4);
  }
  expect_sound_design("reference-x", 0.005360, 1.0, 1.5, 3.0);
}

}  // namespace
}  // namespace tnv::hil
