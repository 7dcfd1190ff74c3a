#include "firmware/supervisor/supervisor.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace tnv::fw {
namespace {

SupervisorInput healthy() {
  SupervisorInput in;
  in.tick = 42;
  in.servo_on = true;
  for (auto& a : in.axis) a = {6.0, 2.0, 6.0, 2.0, 2.0};
  return in;
}

TEST(Supervisor, HealthyTickRaisesNothing) { EXPECT_FALSE(check(SupervisorConfig{}, healthy()).active()); }

TEST(Supervisor, FollowingErrorLimitScalesWithCommandedSpeedAboveAFloor) {
  const SupervisorConfig cfg;
  const FollowingErrorLimit& lim = cfg.axis[0].following;
  EXPECT_DOUBLE_EQ(lim.at(0.0), lim.floor_mm);
  EXPECT_DOUBLE_EQ(lim.at(-100.0), lim.floor_mm + lim.lag_s * 100.0);

  SupervisorInput in = healthy();
  in.axis[1].reference_speed_mm_s = 0.0;
  in.axis[1].position_mm = 6.0 - 0.99 * lim.floor_mm;
  EXPECT_FALSE(check(cfg, in).active());
  in.axis[1].position_mm = 6.0 - 1.01 * lim.floor_mm;
  const FaultRecord f = check(cfg, in);
  EXPECT_EQ(f.reason, FaultReason::following_error);
  EXPECT_EQ(f.axis, 1);
  EXPECT_EQ(f.tick, 42u);
  EXPECT_NEAR(f.value, 1.01 * lim.floor_mm, 1e-12) << "recorded error, mm";
  // The same error at 100 mm/s commanded is inside the scaled limit.
  in.axis[1].reference_speed_mm_s = 100.0;
  EXPECT_FALSE(check(cfg, in).active());
}

TEST(Supervisor, FollowingErrorIsNotCheckedWithServoOff) {
  SupervisorInput in = healthy();
  in.servo_on = false;
  in.axis[0].position_mm = 7.0;
  EXPECT_FALSE(check(SupervisorConfig{}, in).active());
}

TEST(Supervisor, EachInputFaultHasItsReason) {
  const SupervisorConfig cfg;
  struct InputCase {
    void (*arm)(SupervisorInput&);
    FaultReason reason;
  };
  const InputCase cases[] = {
      {[](SupervisorInput& i) { i.bus_ok = false; }, FaultReason::bus_error},
      {[](SupervisorInput& i) { i.snapshot_advanced = false; }, FaultReason::stale_snapshot},
      {[](SupervisorInput& i) { i.ticks_missed = 3; }, FaultReason::missed_ticks},
      {[](SupervisorInput& i) { i.inputs.estop = true; }, FaultReason::estop},
      {[](SupervisorInput& i) { i.inputs.watchdog_tripped = true; }, FaultReason::watchdog_tripped},
      {[](SupervisorInput& i) { i.inputs.servo_alarm[1] = true; }, FaultReason::servo_alarm},
      {[](SupervisorInput& i) { i.inputs.limit_negative[0] = true; }, FaultReason::limit_switch},
      {[](SupervisorInput& i) { i.axis[0].position_mm = 300.0; }, FaultReason::position_limit},
      {[](SupervisorInput& i) { i.axis[1].speed_mm_s = -151.0; }, FaultReason::speed_limit},
      {[](SupervisorInput& i) { i.axis[0].command_mm_s = std::numeric_limits<double>::quiet_NaN(); },
       FaultReason::non_finite_command},
      {[](SupervisorInput& i) { i.axis[0].position_mm = std::numeric_limits<double>::quiet_NaN(); },
       FaultReason::following_error},
  };
  for (const InputCase& c : cases) {
    SupervisorInput in = healthy();
    c.arm(in);
    EXPECT_EQ(check(cfg, in).reason, c.reason) << to_string(c.reason);
  }
  SupervisorInput two_missed = healthy();
  two_missed.ticks_missed = 2;
  EXPECT_FALSE(check(cfg, two_missed).active()) << "up to max_consecutive_missed_ticks is tolerated";
}

TEST(Supervisor, ConfigValidationRejectsNonsense) {
  EXPECT_STREQ(validate(SupervisorConfig{}), "");
  SupervisorConfig c;
  c.axis[1].following.floor_mm = 0.0;
  EXPECT_NE(std::string(validate(c)), "");
  c = {};
  c.axis[0].position_min_mm = 10.0;
  c.axis[0].position_max_mm = -10.0;
  EXPECT_NE(std::string(validate(c)), "");
  c = {};
  c.axis[0].speed_max_mm_s = std::numeric_limits<double>::infinity();
  EXPECT_NE(std::string(validate(c)), "");
}

}  // namespace
}  // namespace tnv::fw
