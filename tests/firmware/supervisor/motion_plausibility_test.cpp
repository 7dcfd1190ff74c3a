// Motion plausibility (motion_plausibility.hpp): the count step the model
// allows, and a table that speeds up against its command.
#include "firmware/supervisor/motion_plausibility.hpp"

#include <gtest/gtest.h>

#include "firmware/supervisor/supervisor.hpp"

namespace tnv::fw {
namespace {

constexpr double kTestCountMm = 10.0 / 24000.0;
constexpr double kTestFullScaleMmS = 1000.0 * 10.0 / 60.0;

// A table stepped exactly (no disturbance) by the paper's X model, or,
// with tau_s > 0, by the continuous law of axis_plant.hpp
// (tau dv/dt = K u - f(v) - v) in 10 us sub-steps, with Coulomb friction
// and stiction (Karnopp: held at rest while |K u| <= stiction).
struct PlausibilityModelTable {
  AxisModel model{};
  double tau_s = 0.0;  // > 0: a continuous plant that can differ from the model
  double gain = 1.0;
  double coulomb_mm_s = 0.0;
  double stiction_mm_s = 0.0;
  double position_mm = 0.0;
  double speed_mm_s = 0.0;
  double drive_sign = 1.0;  // -1: the drive's gain sign flipped
  void step(double u_mm_s) {
    const double drive = drive_sign * gain * u_mm_s;
    if (tau_s <= 0.0) {
      const double p = position_mm + model.A(0, 1) * speed_mm_s + model.B(0) * drive;
      speed_mm_s = model.A(1, 1) * speed_mm_s + model.B(1) * drive;
      position_mm = p;
      return;
    }
    constexpr int kSubsteps = 100;
    const double dt = kControlPeriod_s / kSubsteps;
    for (int i = 0; i < kSubsteps; ++i) {
      if (speed_mm_s == 0.0 && std::fabs(drive) <= stiction_mm_s) continue;  // stuck
      const double moving = speed_mm_s != 0.0 ? speed_mm_s : drive;
      const double w = drive - std::copysign(coulomb_mm_s, moving);
      const double decay = std::exp(-dt / tau_s);
      const double v = decay * speed_mm_s + (1.0 - decay) * w;
      position_mm += (dt - tau_s * (1.0 - decay)) * w + tau_s * (1.0 - decay) * speed_mm_s;
      // Friction stops the table; it cannot turn it.
      speed_mm_s = coulomb_mm_s > 0.0 && v * speed_mm_s < 0.0 ? 0.0 : v;
    }
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

TEST(MotionPlausibility, AFlippedDriveAtJogSpeedIsFoundBeforeTheTableTurns) {
  // Jogging at a steady command on the exact model; the drive flips at a
  // tick. w = (dp_k - A22 dp_{k-1}) / (B1 + C) is -u from the second tick on,
  // while the table still moves the commanded way (the step check needs it
  // to turn: 4 ticks, about 40 um at 20 mm/s).
  for (const double u : {20.0, -20.0, 50.0}) {
    for (const double offset_counts : {0.0, 0.3, 0.7}) {
      SCOPED_TRACE(::testing::Message() << "u " << u << " offset " << offset_counts);
      MonitorRun r;
      r.table.position_mm = offset_counts * kTestCountMm;
      for (int k = 0; k < 60; ++k) ASSERT_FALSE(r.tick(u).runaway_push) << k;
      PlausibilityModelTable healthy = r.table;
      r.table.drive_sign = -1.0;
      int ticks = 0;
      PlausibilityVerdict v;
      while (!v.runaway_push && !v.runaway && ticks < 10) {
        ++ticks;
        healthy.step(u);
        v = r.tick(u);
      }
      EXPECT_TRUE(v.runaway_push);
      EXPECT_FALSE(v.jump);
      EXPECT_LE(ticks, 2);
      EXPECT_GT(v.push_against_mm_s, v.push_limit_mm_s);
      EXPECT_GT(r.table.speed_mm_s * u, 0.0) << "found while the table still moves the commanded way";
      if (std::fabs(u) <= 20.0) {
        EXPECT_LT(std::fabs(healthy.position_mm - r.table.position_mm) * 1e3, 20.0) << "um off";
      }
    }
  }
}

TEST(MotionPlausibility, ASlowWeakTableBrakingFrom100IsNotARunaway) {
  // The 47 Hz table of StructuralModeShaper.*: tau 9 ms, K 0.9, friction
  // 2.0 / 3.2 mm/s against the model's 5.4 ms and 1.0 (it braked a 100 mm/s
  // move and tripped an earlier residual-based design). Its w is about
  // 0.56 u + 0.38 v: with the command unless the table runs against it at
  // over twice the command.
  const auto slow_table = [] {
    MonitorRun r;
    r.table.tau_s = 0.009;
    r.table.gain = 0.9;
    r.table.coulomb_mm_s = 2.0;
    r.table.stiction_mm_s = 3.2;
    return r;
  };
  const auto expect_quiet = [](MonitorRun& r, double u, int k) {
    const PlausibilityVerdict v = r.tick(u);
    EXPECT_FALSE(v.runaway_push) << "tick " << k << " u " << u << ": w against by " << v.push_against_mm_s
                                 << " mm/s, limit " << v.push_limit_mm_s;
    EXPECT_FALSE(v.runaway) << "tick " << k;
    EXPECT_FALSE(v.jump) << "tick " << k;
  };
  // A move the model's inverse drives (u = v_ref + tau a_ref) at 5000 mm/s^2
  // (ten times the path planner's default): up to 100 mm/s, hold, brake
  // through 0 to -100 mm/s, hold, stop.
  MonitorRun r = slow_table();
  const double tau_model_s = 0.005366;
  const auto ramp = [&](double from, double to, int ticks, int& k) {
    const double a = (to - from) / (ticks * kControlPeriod_s);
    for (int i = 0; i < ticks; ++i, ++k) expect_quiet(r, from + (to - from) * i / ticks + tau_model_s * a, k);
  };
  int k = 0;
  for (; k < 20; ++k) expect_quiet(r, 0.0, k);
  ramp(0.0, 100.0, 20, k);
  for (int i = 0; i < 100; ++i, ++k) expect_quiet(r, 100.0, k);
  ramp(100.0, -100.0, 40, k);
  for (int i = 0; i < 100; ++i, ++k) expect_quiet(r, -100.0, k);
  ramp(-100.0, 0.0, 20, k);
  for (int i = 0; i < 50; ++i, ++k) expect_quiet(r, 0.0, k);
  // Braked by a step of the command, held, the way it points.
  MonitorRun step = slow_table();
  for (int i = 0; i < 100; ++i) expect_quiet(step, 100.0, i);
  for (int i = 0; i < 100; ++i) expect_quiet(step, 10.0, 100 + i);
  // Braked by a command pointing back, as the loop does when this table
  // lags a 5000 mm/s^2 stop (on the rig: -15..-25 mm/s with the table still
  // at +50): w is about 0.56 u + 0.38 v, 23 mm/s against, while the table
  // runs against the command; the push check waits until it moves with it.
  MonitorRun back = slow_table();
  for (int i = 0; i < 100; ++i) expect_quiet(back, 100.0, i);
  for (int i = 0; i < 100; ++i) expect_quiet(back, -20.0, 100 + i);
}

TEST(MotionPlausibility, FrictionIsNotARunaway) {
  // Friction opposes the motion: w = K u - f_c sign(v), with the command
  // while K u > f_c, 0 while stuck. The heaviest friction of the tables
  // here (2.5 / 4.0 mm/s, slow-heavy) and one three times it.
  for (const double coulomb : {2.5, 7.5}) {
    SCOPED_TRACE(::testing::Message() << "coulomb " << coulomb);
    MonitorRun r;
    r.table.tau_s = 0.005366;
    r.table.coulomb_mm_s = coulomb;
    r.table.stiction_mm_s = 1.6 * coulomb;
    // Jog at 10 mm/s from rest, stop, the other way.
    for (int k = 0; k < 400; ++k) {
      const double u = k < 100 ? 10.0 : k < 200 ? 0.0 : k < 300 ? -10.0 : 0.0;
      const PlausibilityVerdict v = r.tick(u);
      EXPECT_FALSE(v.runaway_push) << k << ": w against by " << v.push_against_mm_s << " limit " << v.push_limit_mm_s;
      EXPECT_FALSE(v.runaway) << k;
    }
    // Reversals: u = 30 sin(2 pi 5 t), each one through stiction.
    for (int k = 0; k < 1000; ++k) {
      const double u = 30.0 * std::sin(2.0 * 3.141592653589793 * 5.0 * k * kControlPeriod_s);
      const PlausibilityVerdict v = r.tick(u);
      EXPECT_FALSE(v.runaway_push) << k << ": w against by " << v.push_against_mm_s << " limit " << v.push_limit_mm_s;
      EXPECT_FALSE(v.runaway) << k;
    }
  }
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
  in.axis[0].plausibility = {};
  in.axis[0].plausibility.runaway_push = true;
  in.axis[0].plausibility.push_against_mm_s = 19.5;
  EXPECT_EQ(check(SupervisorConfig{}, in).reason, FaultReason::runaway);
  EXPECT_EQ(check(SupervisorConfig{}, in).value, 19.5) << "mm/s of input against the command";
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
  c.axis[0].plausibility.runaway_push_fraction = 0.0;
  EXPECT_STRNE(validate(c), "");
  c = {};
  c.axis[1].plausibility.runaway_push_min_command_mm_s = 0.5;
  EXPECT_STRNE(validate(c), "");
  c = {};
  EXPECT_STREQ(validate(c), "");
}

}  // namespace
}  // namespace tnv::fw
