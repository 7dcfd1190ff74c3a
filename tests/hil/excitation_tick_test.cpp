// TickTask::start_excitation (issue 7): only while holding, a bad spec is
// refused, one at a time, the supervisor stays quiet (the reference follows
// the table), the axis holds where it came to rest, disable cancels it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "emulator/scenario_file.hpp"
#include "tools/hil/hil_rig.hpp"

namespace tnv::hil {
namespace {

std::unique_ptr<HilRig> rig_for_no_cut() {
  std::string error;
  auto rig = HilRig::create(*emu::builtin_scenario("no-cut"), fw::default_firmware_config(), fw::ControllerKind::rdvsc,
                            error);
  EXPECT_NE(rig, nullptr) << error;
  if (rig) rig->home();
  return rig;
}

fw::ExcitationSpec step(double level_mm_s) {
  fw::ExcitationSpec s;
  s.kind = fw::ExcitationKind::step;
  s.level_mm_s = level_mm_s;
  s.duration_s = 0.05;
  s.settle_s = 0.1;
  return s;
}

TEST(ExcitationTick, OnlyWhileHoldingAndOnlyAValidSpec) {
  auto rig = rig_for_no_cut();
  ASSERT_NE(rig, nullptr);
  EXPECT_EQ(rig->task.start_excitation(hal::Axis::x, step(5.0)), fw::CommandStatus::busy);  // servo off
  ASSERT_EQ(rig->task.hold_position(), fw::CommandStatus::ok);
  for (int k = 0; k < 50; ++k) rig->tick();
  EXPECT_EQ(rig->task.start_excitation(hal::Axis::x, step(std::numeric_limits<double>::quiet_NaN())),
            fw::CommandStatus::invalid);
  EXPECT_FALSE(rig->task.exciting());
  ASSERT_EQ(rig->task.start_excitation(hal::Axis::x, step(5.0)), fw::CommandStatus::ok);
  EXPECT_TRUE(rig->task.exciting());
  EXPECT_EQ(rig->task.start_excitation(hal::Axis::y, step(5.0)), fw::CommandStatus::busy);  // one at a time
}

TEST(ExcitationTick, OpenLoopStepMovesTheAxisThenItHoldsThere) {
  auto rig = rig_for_no_cut();
  ASSERT_NE(rig, nullptr);
  ASSERT_EQ(rig->task.hold_position(), fw::CommandStatus::ok);
  for (int k = 0; k < 50; ++k) rig->tick();
  const double x0 = rig->task.last_record().axis[0].position_mm;
  const double y0 = rig->task.last_record().axis[1].position_mm;
  ASSERT_EQ(rig->task.start_excitation(hal::Axis::x, step(10.0)), fw::CommandStatus::ok);
  int ticks = 0;
  while (rig->task.exciting() && ticks < 1000) {
    rig->tick();
    ++ticks;
    const fw::AxisTickRecord& x = rig->task.last_record().axis[0];
    if (rig->task.exciting()) {
      EXPECT_EQ(x.reference_mm, x.position_mm) << "tick " << ticks;
    }
  }
  EXPECT_EQ(rig->task.state(), fw::MotionState::holding) << fw::to_string(rig->task.fault().reason);
  // 50 ms at (10 - f_c) mm/s less the lag: about 0.4 mm; well above zero, well below the open-loop bound.
  const double moved_mm = rig->task.last_record().axis[0].position_mm - x0;
  EXPECT_GT(moved_mm, 0.2) << "x moved " << moved_mm << " mm";
  EXPECT_LT(moved_mm, 0.6) << "x moved " << moved_mm << " mm";
  EXPECT_NEAR(rig->task.last_record().axis[1].position_mm, y0, 2e-3) << "y must hold";
  // Holding after: the axis stays where it came to rest.
  const double rest_mm = rig->task.last_record().axis[0].position_mm;
  for (int k = 0; k < 200; ++k) rig->tick();
  EXPECT_NEAR(rig->task.last_record().axis[0].position_mm, rest_mm, 2e-3);
  EXPECT_EQ(rig->task.state(), fw::MotionState::holding);
}

// A multisine on a carrier: the reference ramps to the carrier's speed,
// moves at it through the drive phase, ramps out and rests exactly carrier x
// drive phase away; the supervisor stays quiet, and a carrier whose travel
// would leave the soft limits is refused.
TEST(ExcitationTick, CarrierMovesTheHoldingReferenceAtItsSpeedThenRests) {
  auto rig = rig_for_no_cut();
  ASSERT_NE(rig, nullptr);
  ASSERT_EQ(rig->task.hold_position(), fw::CommandStatus::ok);
  for (int k = 0; k < 50; ++k) rig->tick();
  const double x0 = rig->task.last_record().axis[0].reference_mm;
  fw::ExcitationSpec spec;
  spec.kind = fw::ExcitationKind::multisine;
  spec.level_mm_s = 2.0;
  spec.f_min_hz = 10.0;
  spec.f_max_hz = 200.0;
  spec.tones = 10;
  spec.duration_s = 1.0;
  spec.carrier_mm_s = -3.0;
  fw::ExcitationSpec too_far = spec;
  too_far.carrier_mm_s = 20.0;
  too_far.duration_s = 40.0;  // 800 mm: beyond the 250 mm soft limit
  EXPECT_EQ(rig->task.start_excitation(hal::Axis::x, too_far), fw::CommandStatus::invalid);
  EXPECT_FALSE(rig->task.exciting());
  ASSERT_EQ(rig->task.start_excitation(hal::Axis::x, spec), fw::CommandStatus::ok);
  int ticks = 0;
  double worst_speed_error = 0.0, previous_speed = 0.0, previous_reference = x0;
  const double max_speed_step = 3.0 / static_cast<double>(fw::kCarrierRampTicks) + 1e-12;
  while (rig->task.exciting() && ticks < 3000) {
    rig->tick();
    ++ticks;
    const fw::AxisTickRecord& x = rig->task.last_record().axis[0];
    // The reference moves by last tick's speed, and its speed never steps.
    EXPECT_NEAR(x.reference_mm, previous_reference + previous_speed * 1e-3, 1e-9) << "tick " << ticks;
    EXPECT_LE(std::fabs(x.reference_speed_mm_s - previous_speed), max_speed_step) << "tick " << ticks;
    if (ticks > fw::kCarrierRampTicks && ticks <= 1000) {
      EXPECT_EQ(x.reference_speed_mm_s, -3.0) << "tick " << ticks;
      if (ticks > 300) worst_speed_error = std::fmax(worst_speed_error, std::fabs(x.speed_mm_s + 3.0));
    }
    if (ticks > 1000 + fw::kCarrierRampTicks) {
      EXPECT_NEAR(x.reference_mm, x0 - 3.0, 1e-9) << "tick " << ticks;
    }
    previous_speed = x.reference_speed_mm_s;
    previous_reference = x.reference_mm;
  }
  EXPECT_NEAR(ticks, 1200, 2);  // the drive phase, then the 0.2 s settle
  EXPECT_EQ(rig->task.state(), fw::MotionState::holding) << fw::to_string(rig->task.fault().reason);
  for (int k = 0; k < 200; ++k) rig->tick();
  EXPECT_NEAR(rig->task.last_record().axis[0].position_mm, x0 - 3.0, 2e-3);
  EXPECT_NEAR(rig->task.last_record().axis[0].reference_mm, x0 - 3.0, 1e-9);
  ::testing::Test::RecordProperty("worst_speed_error_mm_s", std::to_string(worst_speed_error));
}

TEST(ExcitationTick, DisableCancelsIt) {
  auto rig = rig_for_no_cut();
  ASSERT_NE(rig, nullptr);
  ASSERT_EQ(rig->task.hold_position(), fw::CommandStatus::ok);
  for (int k = 0; k < 50; ++k) rig->tick();
  ASSERT_EQ(rig->task.start_excitation(hal::Axis::y, step(-5.0)), fw::CommandStatus::ok);
  for (int k = 0; k < 10; ++k) rig->tick();
  ASSERT_EQ(rig->task.disable(), fw::CommandStatus::ok);
  rig->tick();
  EXPECT_FALSE(rig->task.exciting());
  EXPECT_EQ(rig->task.last_record().axis[1].command_mm_s, 0.0);
}

}  // namespace
}  // namespace tnv::hil
