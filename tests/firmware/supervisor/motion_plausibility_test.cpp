// Motion plausibility (motion_plausibility.hpp): the count step the model
// allows, and a table that speeds up against its command.
#include "firmware/supervisor/motion_plausibility.hpp"

#include <gtest/gtest.h>

#include "firmware/supervisor/supervisor.hpp"

namespace tnv::fw {
namespace {

constexpr double kTestCountMm = 10.0 / 24000.0;
constexpr double kTestFullScaleMmS = 1000.0 * 10.0 / 60.0;

// The paper's X model, stepped exactly (no disturbance) from `counts`.
struct PlausibilityModelTable {
  AxisModel model{};
  double position_mm = 0.0;
  double speed_mm_s = 0.0;
  double drive_sign = 1.0;  // -1: the drive's gain sign flipped
  void step(double u_mm_s) {
    const double w = drive_sign * u_mm_s;
    const double p = position_mm + model.A(0, 1) * speed_mm_s + model.B(0) * w;
    speed_mm_s = model.A(1, 1) * speed_mm_s + model.B(1) * w;
    position_mm = p;
  }
  std::int64_t counts() const { return static_cast<std::int64_t>(std::floor(position_mm / kTestCountMm)); }
};

struct MonitorRun {
  MotionPlausibility monitor;
  PlausibilityModelTable table;
  PlausibilityLimit limit{};
  PlausibilityVerdict tick(double u_mm_s, std::int64_t extra_counts = 0) {
    table.step(u_mm_s);
    return monitor.update(table.counts() + extra_counts, u_mm_s, true, table.model, kTestCountMm, kTestFullScaleMmS, limit);
  }
};

TEST(MotionPlausibility, TheModelsOwnMotionIsPlausibleAtAnyCommand) {
  for (const double u : {0.0, 2.0, -30.0, 150.0, -166.0}) {
    MonitorRun r;
    for (int k = 0; k < 50; ++k) {
      const PlausibilityVerdict v = r.tick(k < 25 ? u : -u);
      EXPECT_FALSE(v.jump) << "u " << u << " tick " << k;
      EXPECT_FALSE(v.runaway) << "u " << u << " tick " << k;
    }
  }
}

TEST(MotionPlausibility, NeedsTwoMeasuredStepsBeforeChecking) {
  MonitorRun r;
  EXPECT_FALSE(r.tick(10.0).checked) << "first count: the base";
  EXPECT_FALSE(r.tick(10.0).checked) << "one step: dp_{k-1} unknown";
  EXPECT_TRUE(r.tick(10.0).checked);
}

TEST(MotionPlausibility, AJumpBeyondTheReachableSpreadIsFlagged) {
  MonitorRun r;
  for (int k = 0; k < 10; ++k) ASSERT_FALSE(r.tick(2.0).jump);
  const PlausibilityVerdict v = r.tick(2.0, 100);
  EXPECT_TRUE(v.jump);
  EXPECT_GT(v.step_mm - v.predicted_mm, v.spread_mm);
  // The X model: (B1 + |C|) x full scale + 3 counts, about 29.6 um.
  EXPECT_NEAR(v.spread_mm, 0.0296, 0.001);
}

TEST(MotionPlausibility, AStopDeadIsNeverAJump) {
  // A jam (or a frozen count) at 150 mm/s: the step drops to 0 at once.
  MonitorRun r;
  for (int k = 0; k < 60; ++k) r.tick(150.0);
  const std::int64_t frozen = r.table.counts();
  for (int k = 0; k < 5; ++k) {
    const PlausibilityVerdict v = r.monitor.update(frozen, 150.0, true, r.table.model, kTestCountMm, kTestFullScaleMmS, r.limit);
    EXPECT_FALSE(v.jump) << k;
    EXPECT_FALSE(v.runaway) << k;
  }
}

TEST(MotionPlausibility, AFlippedDriveIsARunaway) {
  MonitorRun r;
  for (int k = 0; k < 20; ++k) ASSERT_FALSE(r.tick(-5.0).runaway);
  r.table.drive_sign = -1.0;
  int ticks = 0;
  bool found = false;
  while (!found && ticks < 20) {
    ++ticks;
    found = r.tick(-5.0 - 5.0 * ticks).runaway;  // the loop pushes harder as the error grows
  }
  EXPECT_TRUE(found);
  EXPECT_LE(ticks, 4);
}

TEST(MotionPlausibility, HuntingAroundZeroIsNotARunaway) {
  // Commands below runaway_min_command_mm_s change sign each tick: no direction.
  MonitorRun r;
  for (int k = 0; k < 40; ++k) EXPECT_FALSE(r.tick(k % 2 == 0 ? 1.5 : -1.5).runaway) << k;
}

TEST(MotionPlausibility, AnInvalidTickRestartsTheHistory) {
  MonitorRun r;
  for (int k = 0; k < 5; ++k) r.tick(10.0);
  // A tick lost: the count moved two ticks' worth; no verdict from it.
  r.table.step(10.0);
  r.table.step(10.0);
  const PlausibilityVerdict v =
      r.monitor.update(r.table.counts() + 1000, 10.0, false, r.table.model, kTestCountMm, kTestFullScaleMmS, r.limit);
  EXPECT_FALSE(v.checked);
  EXPECT_FALSE(r.tick(10.0).checked);
}

TEST(MotionPlausibility, SupervisorNamesTheReasons) {
  SupervisorInput in;
  in.servo_on = true;
  in.axis[1].plausibility.jump = true;
  EXPECT_EQ(check(SupervisorConfig{}, in).reason, FaultReason::encoder_implausible);
  EXPECT_EQ(check(SupervisorConfig{}, in).axis, 1);
  in.axis[1].plausibility = {};
  in.axis[0].plausibility.runaway = true;
  EXPECT_EQ(check(SupervisorConfig{}, in).reason, FaultReason::runaway);
  in.servo_on = false;
  EXPECT_FALSE(check(SupervisorConfig{}, in).active()) << "runaway needs live outputs";
}

TEST(MotionPlausibility, LimitsAreValidated) {
  SupervisorConfig c;
  c.axis[0].plausibility.jump_disturbance_scale = 0.1;
  EXPECT_STRNE(validate(c), "");
  c = {};
  c.axis[1].plausibility.runaway_min_command_mm_s = 0.0;
  EXPECT_STRNE(validate(c), "");
  c = {};
  EXPECT_STREQ(validate(c), "");
}

}  // namespace
}  // namespace tnv::fw
