// Identification on the rig: the firmware's open-loop excitation on the emulated
// table, fitted on the host, against each scenario's true plant values.
// Three tables that differ from the defaults (and from each other) in tau,
// K and friction, plus the reference plant; none of them was used to tune
// the excitation sequence except the reference plant.
#include <gtest/gtest.h>

#include <cmath>

#include "emulator/scenario_file.hpp"
#include "firmware/control/sliding_mode_params.hpp"
#include "tests/sanitized_build.hpp"
#include "tools/hil/tune_identify.hpp"

namespace tnv::hil {
namespace {

using namespace tnv::tune;

struct IdentifyCase {
  const char* name;
  double tau_s;
  double gain;
  double coulomb_mm_s;
  double stiction_mm_s;
};

emu::Scenario scenario_for(const IdentifyCase& c, hal::Axis axis) {
  emu::Scenario s = *emu::builtin_scenario("no-cut");
  s.name = c.name;
  emu::AxisPlantParams& p = s.plant[hal::index(axis)];
  p.tau_s = c.tau_s;
  p.gain = c.gain;
  p.coulomb_mm_s = c.coulomb_mm_s;
  p.stiction_mm_s = c.stiction_mm_s;
  return s;
}

void expect_identified(const IdentifyCase& c, hal::Axis axis) {
  const emu::Scenario s = scenario_for(c, axis);
  const AxisIdentification id = identify_axis_on_emulator(s, axis);
  const char* ax = axis == hal::Axis::x ? "x" : "y";
  ASSERT_TRUE(id.ok) << c.name << " axis " << ax << ": " << id.error;
  EXPECT_NEAR(id.tau_s, c.tau_s, 0.02 * c.tau_s)
      << c.name << " axis " << ax << ": tau " << id.tau_s * 1e3 << " ms, true " << c.tau_s * 1e3 << " ms";
  EXPECT_NEAR(id.gain, c.gain, 0.02 * c.gain) << c.name << " axis " << ax << ": K " << id.gain << ", true " << c.gain;
  EXPECT_NEAR(id.coulomb_mm_s, c.coulomb_mm_s, 0.15 * c.coulomb_mm_s)
      << c.name << " axis " << ax << ": f_c " << id.coulomb_mm_s << " mm/s, true " << c.coulomb_mm_s << " mm/s";
  EXPECT_NEAR(id.stiction_mm_s, c.stiction_mm_s, 0.15 * c.stiction_mm_s)
      << c.name << " axis " << ax << ": f_s " << id.stiction_mm_s << " mm/s, true " << c.stiction_mm_s << " mm/s";
  // The discrete model is the exact zero-order hold of the identified (tau, K).
  const fw::AxisModel exact = fw::zoh_axis_model(c.tau_s, c.gain, 1e-3);
  EXPECT_NEAR(id.model.A(1, 1), exact.A(1, 1), 0.01) << c.name << " axis " << ax << ": A22";
  EXPECT_NEAR(id.model.B(1), exact.B(1), 0.02 * exact.B(1)) << c.name << " axis " << ax << ": B2";
}

// One TEST: each identification is a few simulated seconds.
TEST(AutotuneIdentify, MatchesTrueValuesOnFourTables) {
  const IdentifyCase reference_x{"reference-x", 0.005360, 1.0, 1.5, 3.0};
  const IdentifyCase reference_y{"reference-y", 0.007122, 1.0, 1.5, 3.0};
  const IdentifyCase slow_heavy{"slow-heavy", 0.0120, 0.85, 2.5, 4.0};
  const IdentifyCase fast_light{"fast-light", 0.0030, 1.20, 0.6, 1.4};
  const IdentifyCase sticky{"sticky", 0.0085, 1.05, 1.0, 3.5};
  // Each table is judged alone: a sanitizer build runs the reference X and the sticky table.
  expect_identified(reference_x, hal::Axis::x);
  if (!tnv::test::kSanitizedBuild) {
    expect_identified(reference_y, hal::Axis::y);
    expect_identified(slow_heavy, hal::Axis::x);
    expect_identified(fast_light, hal::Axis::y);
  }
  expect_identified(sticky, hal::Axis::x);
}

}  // namespace
}  // namespace tnv::hil
