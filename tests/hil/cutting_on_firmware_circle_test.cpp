// With the firmware tracking the S1 circle (R-DVSC+DDC in the paper's
// configuration, the table3 runs), the emulator's table-following cutting
// force stays close to the circle model it replaced (v_feed and direction
// from the commanded circle). The difference is exactly
// load(t) R(-135 deg) (v_table - v_commanded): how well the controller
// holds the feed is how close the two are.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "emulator/scenario_file.hpp"
#include "emulator/substep_timing.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tests/emulator/cutting_reference.hpp"
#include "tools/hil/hil_firmware_config.hpp"
#include "tools/hil/hil_rig.hpp"

namespace tnv::hil {
namespace {

using hal::Axis;
namespace ts = emu::test_support;

struct FirmwareCircleRun {
  ts::CircleModelComparison forces;
  double rms_explained_mm_s = 0.0;  // load(t) |v_table - v_commanded|
};

FirmwareCircleRun cutting_on_firmware_circle(const emu::Scenario& s, fw::ControllerKind controller) {
  FirmwareCircleRun r;
  std::string error;
  std::unique_ptr<HilRig> rig = HilRig::create(s, fw::default_firmware_config(), controller, error);
  EXPECT_TRUE(rig) << error;
  if (!rig) return r;
  rig->home();
  EXPECT_EQ(rig->task.start_circle(circle_spec_for(s)), fw::CommandStatus::ok);
  double start_s = -1.0;  // machine time of the commanded circle's start
  double explained_sq = 0.0;
  for (int k = 0; k < 25'000 && rig->task.state() != fw::MotionState::holding; ++k) {
    rig->tick();
    const std::int64_t motion_tick = rig->task.last_record().motion_tick;
    if (motion_tick < 0) continue;
    // The reference of motion tick m is where the table should be at this latch.
    if (start_s < 0.0) start_s = rig->machine.time_s() - static_cast<double>(motion_tick) * kTickPeriodS;
    const double force_s = rig->machine.time_s() - emu::kSubstep_s;  // the sub-step that ended at the latch
    const emu::AxisTruth x = rig->machine.truth(Axis::x), y = rig->machine.truth(Axis::y);
    const ts::PathSample ref = ts::S1Circle{s.circle, start_s}.at(force_s);
    r.forces.add({x.cutting_mm_s, y.cutting_mm_s}, ts::circle_model_cutting(s.cutting, s.circle, start_s, force_s),
                 ref.angle_rad);
    const double velocity_error_mm_s = std::hypot(x.speed_mm_s - ref.vx_mm_s, y.speed_mm_s - ref.vy_mm_s);
    explained_sq += std::pow(ts::cutting_level_mm_s(s.cutting, s.circle.feed_mm_s, force_s, velocity_error_mm_s), 2);
  }
  EXPECT_EQ(rig->task.state(), fw::MotionState::holding) << "the circle ran to its end";
  r.rms_explained_mm_s = std::sqrt(explained_sq / r.forces.samples());
  return r;
}

class CuttingOnTheFirmwareCircle : public ::testing::TestWithParam<const char*> {};

// Measured on the reference plant: 10.0-10.1 % rms apart, the sliding-mode
// loop's speed ripple (its M-method speed moves in 0.42 mm/s steps); the
// means along the feed within 0.15 %, outward 1.7-3 % lower (the load's
// peaks push the travel outward). Asserted with margin: 12 %, 0.5 %, 5 %.
TEST_P(CuttingOnTheFirmwareCircle, StaysCloseToTheCircleModel) {
  const FirmwareCircleRun r = cutting_on_firmware_circle(*emu::builtin_scenario(GetParam()), fw::ControllerKind::rdvsc);
  const ts::CircleModelComparison& c = r.forces;
  ASSERT_GT(c.samples(), 18'900) << "ticks of motion compared";
  EXPECT_LT(c.rms_difference_mm_s(), 0.12 * c.rms_circle_mm_s())
      << "mm/s rms of the difference, against " << c.rms_circle_mm_s() << " mm/s rms of the circle model";
  // The difference is the velocity error, weighted by the load: the truth
  // speed is 10 us later than the one the force used (measured 0.8 % apart).
  EXPECT_NEAR(c.rms_difference_mm_s(), r.rms_explained_mm_s, 0.02 * r.rms_explained_mm_s) << "mm/s rms";
  EXPECT_NEAR(c.along_table_mm_s(), c.along_circle_mm_s(), 0.005 * std::abs(c.along_circle_mm_s()))
      << "mm/s, mean component along the commanded feed";
  EXPECT_LT(c.along_circle_mm_s(), 0.0) << "mm/s: opposing the feed";
  EXPECT_GT(c.outward_table_mm_s(), 0.95 * c.outward_circle_mm_s()) << "mm/s, mean outward component";
  EXPECT_LT(c.outward_table_mm_s(), c.outward_circle_mm_s()) << "mm/s, mean outward component";
}

INSTANTIATE_TEST_SUITE_P(S1Spindles, CuttingOnTheFirmwareCircle, ::testing::Values("cut-900", "cut-1200", "cut-1500"));

}  // namespace
}  // namespace tnv::hil
