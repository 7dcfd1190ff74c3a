// The supervisor's checks for the board's own fault latches and the tick
// period, and what clear_fault() must refuse on.
#include <gtest/gtest.h>

#include <string>

#include "firmware/supervisor/supervisor.hpp"

namespace tnv::fw {
namespace {

SupervisorInput healthy_with_period() {
  SupervisorInput in;
  in.tick = 7;
  in.servo_on = true;
  in.period_clocks = 10'000;
  for (auto& a : in.axis) a = {6.0, 2.0, 6.0, 2.0, 2.0};
  return in;
}

TEST(SupervisorBoardFaults, EncoderAndDacLatchesFaultTheirAxis) {
  const SupervisorConfig cfg;
  SupervisorInput in = healthy_with_period();
  in.inputs.encoder_error[1] = true;
  FaultRecord f = check(cfg, in);
  EXPECT_EQ(f.reason, FaultReason::encoder_error);
  EXPECT_EQ(f.axis, 1);
  EXPECT_EQ(f.tick, 7u);
  in = healthy_with_period();
  in.inputs.dac_error[0] = true;
  in.servo_on = false;  // checked with the servo off too: the board latch is a hardware fault
  f = check(cfg, in);
  EXPECT_EQ(f.reason, FaultReason::dac_error);
  EXPECT_EQ(f.axis, 0);
}

TEST(SupervisorBoardFaults, PeriodBeyondHalfATickIsALateTick) {
  const SupervisorConfig cfg;
  SupervisorInput in = healthy_with_period();
  in.period_clocks = 15'000;
  EXPECT_FALSE(check(cfg, in).active()) << "exactly the tolerance is accepted";
  in.period_clocks = 15'001;
  const FaultRecord f = check(cfg, in);
  EXPECT_EQ(f.reason, FaultReason::late_tick);
  EXPECT_EQ(f.value, 15'001.0) << "measured period, clocks";
  EXPECT_EQ(f.limit, 10'000.0) << "expected period, clocks";
  in.period_clocks = 4'999;
  EXPECT_EQ(check(cfg, in).reason, FaultReason::late_tick) << "early is as wrong as late";
  in.period_clocks = 0;
  EXPECT_FALSE(check(cfg, in).active()) << "0 = not measured: unchecked";
}

TEST(SupervisorBoardFaults, PeriodIsJudgedOverTheTicksItSpans) {
  const SupervisorConfig cfg;
  SupervisorInput in = healthy_with_period();
  in.ticks_missed = 2;  // tolerated, and the period spans 3 nominal periods
  in.period_clocks = 30'000;
  EXPECT_FALSE(check(cfg, in).active());
  in.period_clocks = 20'000;  // 3 sequence steps in 2 periods: the board's clock is wrong
  EXPECT_EQ(check(cfg, in).reason, FaultReason::late_tick);
}

TEST(SupervisorBoardFaults, ConfigRejectsBadPeriodSettings) {
  SupervisorConfig cfg;
  cfg.period_tolerance_clocks = 0;
  EXPECT_NE(std::string(validate(cfg)), "");
  cfg.period_tolerance_clocks = cfg.tick_period_clocks;
  EXPECT_NE(std::string(validate(cfg)), "");
  cfg = {};
  cfg.tick_period_clocks = 0;
  EXPECT_NE(std::string(validate(cfg)), "");
}

TEST(SupervisorBoardFaults, CausePresentCoversEveryLatchedInput) {
  EXPECT_FALSE(fault_cause_present({}));
  const auto with = [](void (*arm)(hal::DiscreteInputs&)) {
    hal::DiscreteInputs in;
    arm(in);
    return fault_cause_present(in);
  };
  EXPECT_TRUE(with([](hal::DiscreteInputs& i) { i.estop = true; }));
  EXPECT_TRUE(with([](hal::DiscreteInputs& i) { i.watchdog_tripped = true; }));
  EXPECT_TRUE(with([](hal::DiscreteInputs& i) { i.servo_alarm[1] = true; }));
  EXPECT_TRUE(with([](hal::DiscreteInputs& i) { i.limit_positive[0] = true; }));
  EXPECT_TRUE(with([](hal::DiscreteInputs& i) { i.limit_negative[1] = true; }));
  EXPECT_TRUE(with([](hal::DiscreteInputs& i) { i.encoder_error[0] = true; }));
  EXPECT_TRUE(with([](hal::DiscreteInputs& i) { i.dac_error[1] = true; }));
}

}  // namespace
}  // namespace tnv::fw
