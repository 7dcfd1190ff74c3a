// The following-error limit on the HIL rig: it scales with the commanded
// speed (floor + lag x |speed|), and the input shaper's delay is not counted
// as following error (the check is against the shaped reference).
#include <gtest/gtest.h>

#include <cmath>

#include "emulator/scenario_file.hpp"
#include "tests/hil/hil_rig.hpp"
#include "tools/hil/hil_firmware_config.hpp"

namespace tnv::hil {
namespace {

namespace regs = hal::regs;

// X cannot move at all: stiction beyond the DAC's full-scale command.
emu::Scenario jammed_x() {
  emu::Scenario s = *emu::builtin_scenario("no-cut");
  s.plant[0].coulomb_mm_s = 200.0;
  s.plant[0].stiction_mm_s = 200.0;
  return s;
}

// The stall monitor would name the jam first (encoder_stall, no count
// while driven hard): set out of reach here, the following error is the
// subject. FaultEncoder covers the stall monitor.
fw::FirmwareConfig following_error_only() {
  fw::FirmwareConfig c = fw::default_firmware_config();
  for (auto& a : c.supervisor.axis) a.stall.command_mm_s = 1e4;
  return c;
}

struct Trip {
  fw::FaultRecord fault{};
  double reference_speed_mm_s = 0.0;  // the commanded (reference) speed on the tripping tick
  bool safe = false;                  // board outputs after that tick
};

Trip run_until_trip(test::HilRig& rig) {
  Trip trip;
  for (int k = 0; k < 20'000 && rig.task.state() != fw::MotionState::faulted; ++k) rig.tick();
  trip.fault = rig.task.fault();
  trip.reference_speed_mm_s = rig.task.last_record().axis[0].reference_speed_mm_s;
  trip.safe = rig.machine.board_outputs().safe(2048);
  return trip;
}

TEST(FaultFollowingError, TheLimitScalesWithTheCommandedSpeed) {
  const fw::FollowingErrorLimit limit = fw::default_firmware_config().supervisor.axis[0].following;
  // At 2 mm/s (the S1 circle) and at 40 mm/s (a move), the jammed axis trips
  // when the error crosses floor + lag x |reference speed| of that tick.
  test::HilRig slow(jammed_x(), following_error_only());
  for (int i = 0; i < 3; ++i) slow.tick();
  ASSERT_EQ(slow.task.start_circle(circle_spec_for(slow.scenario)), fw::CommandStatus::ok);
  const Trip at_circle = run_until_trip(slow);

  test::HilRig fast(jammed_x(), following_error_only());
  for (int i = 0; i < 3; ++i) fast.tick();
  ASSERT_EQ(fast.task.hold_position(), fw::CommandStatus::ok);
  fast.tick();
  ASSERT_EQ(fast.task.start_move({hal::Axis::x, 20.0, 40.0, 0.02, 0.0}), fw::CommandStatus::ok);
  const Trip at_move = run_until_trip(fast);

  for (const Trip* t : {&at_circle, &at_move}) {
    EXPECT_EQ(t->fault.reason, fw::FaultReason::following_error);
    EXPECT_EQ(t->fault.axis, 0);
    EXPECT_TRUE(t->safe);
    EXPECT_NEAR(t->fault.limit, limit.at(t->reference_speed_mm_s), 1e-12) << "mm";
    EXPECT_GT(std::fabs(t->fault.value), t->fault.limit) << "mm";
    // Tripped within one tick of travel after crossing.
    EXPECT_LT(std::fabs(t->fault.value) - t->fault.limit, std::fabs(t->reference_speed_mm_s) * 1e-3 + 1e-9) << "mm";
  }
  EXPECT_NEAR(at_move.reference_speed_mm_s, 40.0, 1e-9) << "tripped at cruise";
  EXPECT_NEAR(at_move.fault.limit, limit.floor_mm + limit.lag_s * 40.0, 1e-12) << "mm";
  EXPECT_LT(at_circle.fault.limit, 0.1) << "mm: at 2 mm/s the limit stays near the floor";
  EXPECT_GT(at_move.fault.limit, 8.0 * at_circle.fault.limit) << "a fixed limit would be blind or trip-happy";
}

TEST(FaultFollowingError, TheShaperDelayIsNotFollowingError) {
  // A 10 Hz ZVD delays the reference by 50 ms: 2 mm at 40 mm/s, well beyond
  // the 0.85 mm limit at that speed. Measured against the shaped reference
  // (what the loop follows) the move runs clean.
  test::HilRig rig(*emu::builtin_scenario("no-cut"));
  ASSERT_TRUE(rig.init_ok);
  ASSERT_EQ(rig.task.configure_shaper(hal::Axis::x, {fw::ShaperType::zvd, {10.0, 0.0}, {0.0, 0.0}}),
            fw::CommandStatus::ok);
  ASSERT_EQ(rig.task.enable_shaper(hal::Axis::x, true), fw::CommandStatus::ok);
  for (int i = 0; i < 3; ++i) rig.tick();
  ASSERT_EQ(rig.task.hold_position(), fw::CommandStatus::ok);
  rig.tick();
  ASSERT_NEAR(rig.task.shaper_delay_s(hal::Axis::x), 0.05, 1e-3) << "s";
  ASSERT_EQ(rig.task.start_move({hal::Axis::x, 20.0, 40.0, 0.02, 0.0}), fw::CommandStatus::ok);
  const fw::FollowingErrorLimit limit = rig.task.config().supervisor.axis[0].following;
  double worst_shaped_share = 0.0, worst_unshaped_excess_mm = -1e9;
  for (int k = 0; k < 5000 && rig.task.state() == fw::MotionState::moving; ++k) {
    rig.tick();
    const fw::AxisTickRecord& r = rig.task.last_record().axis[0];
    const double lim_mm = limit.at(r.reference_speed_mm_s);
    worst_shaped_share = std::max(worst_shaped_share, std::fabs(r.reference_mm - r.position_mm) / lim_mm);
    worst_unshaped_excess_mm =
        std::max(worst_unshaped_excess_mm, std::fabs(r.unshaped_reference_mm - r.position_mm) - lim_mm);
  }
  EXPECT_EQ(rig.task.state(), fw::MotionState::holding) << "fault: " << fw::to_string(rig.task.fault().reason);
  EXPECT_LT(worst_shaped_share, 0.5) << "share of the limit used against the shaped reference";
  EXPECT_GT(worst_unshaped_excess_mm, 0.5) << "mm beyond the limit: a delay-blind check would have tripped";
  EXPECT_NE(rig.machine.board_outputs().enabled[0], false) << "still servoing";
}

}  // namespace
}  // namespace tnv::hil
