// Issue 7, item 3: the firmware's friction feed-forward, switched on with
// the papers' R-DVSC+DDC gains and the identified Coulomb friction, takes
// the quadrant-reversal glitch down on the seed-0 no-cut circle; switched
// off (the default) the run is bit for bit the papers' configuration.
#include <gtest/gtest.h>

#include "emulator/scenario_file.hpp"
#include "tools/hil/best_circle.hpp"
#include "tools/hil/circle_run.hpp"
#include "tools/hil/tune_identify.hpp"

namespace tnv::hil {
namespace {

using namespace tnv::tune;

TEST(FrictionFeedForwardCircle, CoulombFeedForwardLowersTheReversalGlitch) {
  const emu::Scenario no_cut = *emu::builtin_scenario("no-cut");
  std::array<fw::FrictionFeedForward, 2> friction{};
  for (std::size_t i = 0; i < 2; ++i) {
    const AxisIdentification id = identify_axis_on_emulator(no_cut, hal::axis_from_index(i));
    ASSERT_TRUE(id.ok) << id.error;
    friction[i] = friction_feedforward_from(id);
  }
  const fw::FirmwareConfig papers = fw::default_firmware_config();
  const fw::FirmwareConfig compensated = with_friction_feedforward(papers, friction);
  const CircleRunResult off = run_circle(no_cut, papers, fw::ControllerKind::rdvsc);
  const CircleRunResult on = run_circle(no_cut, compensated, fw::ControllerKind::rdvsc);
  ASSERT_TRUE(off.completed) << off.error;
  ASSERT_TRUE(on.completed) << on.error;
  EXPECT_LT(on.stats.max_um, 0.8 * off.stats.max_um)
      << "max contour error with feed-forward " << on.stats.max_um << " um, without " << off.stats.max_um << " um";
  EXPECT_LT(on.stats.std_um, off.stats.std_um)
      << "std with feed-forward " << on.stats.std_um << " um, without " << off.stats.std_um << " um";
}

TEST(FrictionFeedForwardCircle, DisabledFeedForwardChangesNothing) {
  const emu::Scenario no_cut = *emu::builtin_scenario("no-cut");
  fw::FirmwareConfig config = fw::default_firmware_config();
  const CircleRunResult a = run_circle(no_cut, config, fw::ControllerKind::rdvsc);
  for (auto& axis : config.axis) {
    axis.friction.coulomb_mm_s = 2.0;  // parameters set, switch off
    axis.friction.stiction_mm_s = 2.5;
  }
  const CircleRunResult b = run_circle(no_cut, config, fw::ControllerKind::rdvsc);
  ASSERT_TRUE(a.completed && b.completed);
  EXPECT_EQ(a.stats.max_um, b.stats.max_um);
  EXPECT_EQ(a.stats.mean_um, b.stats.mean_um);
  EXPECT_EQ(a.stats.std_um, b.stats.std_um);
}

}  // namespace
}  // namespace tnv::hil
