// Issue 7: the speed observer (firmware/control/speed_observer.hpp) on the
// HIL rig. Off (the firmware default) it changes nothing, bit for bit,
// whatever its gains. On, as tune_design sets it (Kalman gain from the
// identified model, the identified Coulomb friction taken out of its
// model), the seed-0 no-cut circle has a lower mean and std than with the
// M-method speed; without its friction term the observer does worse on
// both the mean and the maximum.
#include <gtest/gtest.h>

#include <cmath>

#include "emulator/scenario_file.hpp"
#include "tools/hil/circle_run.hpp"
#include "tools/hil/tune_identify.hpp"
#include "tools/tune/axis_design.hpp"

namespace tnv::hil {
namespace {

using namespace tnv::tune;

bool observer_same_trace(const CircleRunResult& a, const CircleRunResult& b) {
  if (a.trace.size() != b.trace.size()) return false;
  for (std::size_t k = 0; k < a.trace.size(); ++k)
    for (std::size_t i = 0; i < 2; ++i)
      if (a.trace[k].position_mm[i] != b.trace[k].position_mm[i] ||
          a.trace[k].command_mm_s[i] != b.trace[k].command_mm_s[i] || a.trace[k].s[i] != b.trace[k].s[i])
        return false;
  return true;
}

TEST(SpeedObserverCircle, OffChangesNothingBitForBit) {
  const emu::Scenario no_cut = *emu::builtin_scenario("no-cut");
  fw::FirmwareConfig config = fw::default_firmware_config();
  const CircleRunOptions trace{true};
  const CircleRunResult a = run_circle(no_cut, config, fw::ControllerKind::rdvsc, trace);
  for (auto& axis : config.axis) {
    const fw::ObserverDesign d = design_observer(axis.model, {kObserverSpeedNoise_mm_s, kObserverDisturbanceNoise_mm_s, axis.count_mm});
    ASSERT_TRUE(d.ok);
    axis.observer = d.params;  // gains set, switch off
    axis.observer.use_position = true;
  }
  const CircleRunResult b = run_circle(no_cut, config, fw::ControllerKind::rdvsc, trace);
  ASSERT_TRUE(a.completed && b.completed);
  ASSERT_GT(a.trace.size(), 10000u);
  EXPECT_TRUE(observer_same_trace(a, b)) << "a disabled observer changed the run";
  EXPECT_EQ(a.stats.max_um, b.stats.max_um);
  EXPECT_EQ(a.stats.mean_um, b.stats.mean_um);
}

TEST(SpeedObserverCircle, TheRulesObserverAndItsFrictionTermEachHelp) {
  const emu::Scenario no_cut = *emu::builtin_scenario("no-cut");
  std::array<AxisDesign, 2> d{};
  for (std::size_t i = 0; i < 2; ++i) {
    d[i] = design_axis(identify_axis_on_emulator(no_cut, hal::axis_from_index(i)));
    ASSERT_TRUE(d[i].ok) << d[i].error;
    EXPECT_TRUE(d[i].observer.enabled) << "the rule switches the observer on";
    EXPECT_NEAR(d[i].observer.friction_mm_s, 1.5, 0.05) << "the identified f_c / K, mm/s";
  }
  const fw::FirmwareConfig on = apply_designs(fw::default_firmware_config(), d[0], d[1]);
  fw::FirmwareConfig off = on;
  fw::FirmwareConfig no_friction = on;
  for (std::size_t i = 0; i < 2; ++i) {
    off.axis[i].observer.enabled = false;
    no_friction.axis[i].observer.friction_mm_s = 0.0;
  }
  ASSERT_TRUE(fw::validate(on).ok());
  const CircleRunResult a = run_circle(no_cut, off, fw::ControllerKind::rdvsc);
  const CircleRunResult b = run_circle(no_cut, on, fw::ControllerKind::rdvsc);
  const CircleRunResult c = run_circle(no_cut, no_friction, fw::ControllerKind::rdvsc);
  ASSERT_TRUE(a.completed) << a.error;
  ASSERT_TRUE(b.completed) << b.error;
  ASSERT_TRUE(c.completed) << c.error;
  EXPECT_LT(b.stats.mean_um, a.stats.mean_um) << "mean contour error with the observer " << b.stats.mean_um
                                              << " um, M-method " << a.stats.mean_um << " um";
  EXPECT_LT(b.stats.std_um, a.stats.std_um) << "std with the observer " << b.stats.std_um << " um, M-method "
                                            << a.stats.std_um << " um";
  EXPECT_LT(b.stats.mean_um, c.stats.mean_um) << "mean with the friction term " << b.stats.mean_um
                                              << " um, without " << c.stats.mean_um << " um";
  EXPECT_LT(b.stats.max_um, c.stats.max_um) << "max with the friction term " << b.stats.max_um << " um, without "
                                            << c.stats.max_um << " um";
}

}  // namespace
}  // namespace tnv::hil
