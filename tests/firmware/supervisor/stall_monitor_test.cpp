// The stall monitor (encoder_stall): a frozen count while the drive is
// commanded well beyond the breakaway trips; a slow axis, a weak command
// or outputs that were off do not.
#include "firmware/supervisor/stall_monitor.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "firmware/supervisor/supervisor.hpp"

namespace tnv::fw {
namespace {

TEST(StallMonitor, CountsTicksWithoutACountWhileDrivenHard) {
  const StallLimit lim{.command_mm_s = 8.0, .ticks = 4};
  StallMonitor m;
  EXPECT_EQ(m.update(100, 20.0, true, lim), 0u) << "the first sample only primes";
  EXPECT_EQ(m.update(100, 20.0, true, lim), 1u);
  EXPECT_EQ(m.update(100, -20.0, true, lim), 2u) << "either sign drives";
  EXPECT_EQ(m.update(100, 8.0, true, lim), 3u) << "the level itself counts";
  EXPECT_EQ(m.applied_command_mm_s(), 8.0) << "the command the fault record reports";
  EXPECT_EQ(m.update(101, 20.0, true, lim), 0u) << "one count is motion";
  EXPECT_EQ(m.update(101, 20.0, true, lim), 1u);
}

TEST(StallMonitor, AWeakCommandOrDeadOutputsResetTheCount) {
  const StallLimit lim{.command_mm_s = 8.0, .ticks = 4};
  StallMonitor m;
  m.update(0, 20.0, true, lim);
  m.update(0, 20.0, true, lim);
  ASSERT_EQ(m.stalled_ticks(), 1u);
  EXPECT_EQ(m.update(0, 7.99, true, lim), 0u) << "below the level: a creeping or breaking-away axis";
  m.update(0, 20.0, true, lim);
  EXPECT_EQ(m.update(0, 20.0, false, lim), 0u) << "outputs off over the interval: nothing was driven";
  m.update(0, 20.0, true, lim);
  m.reset();
  EXPECT_EQ(m.update(0, 20.0, true, lim), 0u) << "after a reset the first sample primes again";
}

SupervisorInput stalled_input(std::uint32_t stalled_ticks) {
  SupervisorInput in;
  in.tick = 7;
  in.servo_on = true;
  for (auto& a : in.axis) a = {6.0, 2.0, 6.0, 2.0, 2.0};
  in.axis[1].stalled_ticks = stalled_ticks;
  in.axis[1].stall_command_mm_s = -12.5;
  return in;
}

TEST(StallMonitor, TheSupervisorLatchesEncoderStallAtTheLimit) {
  const SupervisorConfig cfg;
  const std::uint32_t n = cfg.axis[1].stall.ticks;
  EXPECT_FALSE(check(cfg, stalled_input(n - 1)).active());
  const FaultRecord f = check(cfg, stalled_input(n));
  EXPECT_EQ(f.reason, FaultReason::encoder_stall);
  EXPECT_EQ(f.axis, 1);
  EXPECT_EQ(f.tick, 7u);
  EXPECT_EQ(f.value, -12.5) << "the command that did not move the encoder, mm/s";
  EXPECT_EQ(f.limit, cfg.axis[1].stall.command_mm_s);
  SupervisorInput off = stalled_input(n);
  off.servo_on = false;
  EXPECT_FALSE(check(cfg, off).active()) << "servo off: nothing is driven";
}

TEST(StallMonitor, ItComesBeforeTheFollowingErrorItCauses) {
  SupervisorInput in = stalled_input(SupervisorConfig{}.axis[1].stall.ticks);
  in.axis[1].position_mm = 5.0;  // 1 mm behind: following error too
  EXPECT_EQ(check(SupervisorConfig{}, in).reason, FaultReason::encoder_stall);
}

TEST(StallMonitor, BadLimitsAreRefusedByName) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const double level : {0.0, -1.0, nan, std::numeric_limits<double>::infinity()}) {
    SupervisorConfig c;
    c.axis[0].stall.command_mm_s = level;
    EXPECT_STREQ(validate(c), "stall command_mm_s must be > 0 and finite") << level;
  }
  for (const std::uint32_t ticks : {0u, 1001u}) {
    SupervisorConfig c;
    c.axis[1].stall.ticks = ticks;
    EXPECT_STREQ(validate(c), "stall ticks must be 1..1000") << ticks;
  }
  EXPECT_STREQ(validate(SupervisorConfig{}), "");
}

}  // namespace
}  // namespace tnv::fw
