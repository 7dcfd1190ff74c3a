// The spindle's command logic (firmware/spindle/spindle_control.hpp): the
// ramp inside the drive's limit, at-speed, the feed gate, every way it
// stops, and that nothing but start() ever turns it on.
#include "firmware/spindle/spindle_control.hpp"

#include <gtest/gtest.h>

#include <array>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace tnv::fw {
namespace {

constexpr double kSpindleTickS = 0.001;

// A drive and motor for these tests: the reference plant's first-order
// speed loop (tau 0.2 s) with its 6,000 rpm/s slew limit, K = 1 rpm per
// commanded rpm; disabled, it coasts down with the same time constant.
struct SpindleTestDrive {
  double rpm = 0.0;
  void step(const SpindleOutputs& out) {
    const double drive = out.enable ? out.command_rpm : 0.0;
    const double rate = std::clamp((drive - rpm) / 0.2, -kSpindleDriveAccelRpmS, kSpindleDriveAccelRpmS);
    rpm += rate * kSpindleTickS;
  }
};

struct SpindleBench {
  SpindleControl control;
  SpindleTestDrive spindle;
  SpindleOutputs tick() {
    const SpindleOutputs out = control.tick(spindle.rpm, kSpindleTickS);
    spindle.step(out);
    return out;
  }
  int ticks_until_at_speed(int limit) {
    for (int i = 1; i <= limit; ++i) {
      tick();
      if (control.at_speed()) return i;
    }
    return -1;
  }
};

constexpr std::array kAllCauses = {SpindleStopCause::command,      SpindleStopCause::program_end,
                                   SpindleStopCause::abort,        SpindleStopCause::host_timeout,
                                   SpindleStopCause::fault,        SpindleStopCause::estop};

TEST(SpindleControl, StartRampsTheCommandWithinItsAccelerationAndHoldsTheEnable) {
  SpindleBench b;
  ASSERT_EQ(b.control.start(SpindleDirection::forward, 6000.0), SpindleResult::ok);
  const double step_rpm = b.control.params().accel_rpm_s * kSpindleTickS;
  double last = 0.0;
  int ticks_to_target = 0;
  for (int i = 1; i <= 2000; ++i) {
    const SpindleOutputs out = b.tick();
    EXPECT_TRUE(out.enable);
    EXPECT_FALSE(out.reverse);
    EXPECT_LE(out.command_rpm - last, step_rpm + 1e-9);
    EXPECT_GE(out.command_rpm, last);
    if (ticks_to_target == 0 && out.command_rpm == 6000.0) ticks_to_target = i;
    last = out.command_rpm;
  }
  EXPECT_EQ(ticks_to_target, 1200);  // 6000 rpm at 5000 rpm/s
  EXPECT_EQ(b.control.outputs().dac_code, 2048 + 1024);  // half of the 12,000 rpm full scale
}

TEST(SpindleControl, AtSpeedNeedsTheRampDoneAndTheWindowHeld) {
  SpindleBench b;
  EXPECT_TRUE(b.control.feed_permitted()) << "commanded off: feed moves are not held";
  ASSERT_EQ(b.control.start(SpindleDirection::forward, 3000.0), SpindleResult::ok);
  EXPECT_FALSE(b.control.feed_permitted()) << "commanded on, not yet at speed";
  int first_in_window = -1;
  int at_speed_tick = -1;
  for (int i = 1; i <= 3000 && at_speed_tick < 0; ++i) {
    const double measured_rpm = b.spindle.rpm;  // what this tick's control sees
    b.tick();
    const bool window = b.control.outputs().command_rpm == 3000.0 && std::fabs(measured_rpm - 3000.0) <= 150.0;
    if (window && first_in_window < 0) first_in_window = i;
    if (b.control.at_speed()) at_speed_tick = i;
    if (at_speed_tick < 0) {
      EXPECT_FALSE(b.control.feed_permitted()) << "tick " << i;
    }
  }
  ASSERT_GT(first_in_window, 600);  // the ramp alone takes 600 ticks
  EXPECT_EQ(at_speed_tick, first_in_window + static_cast<int>(b.control.params().at_speed_ticks) - 1);
  EXPECT_TRUE(b.control.feed_permitted());
  // A new speed is a new wait.
  ASSERT_EQ(b.control.set_speed(4000.0), SpindleResult::ok);
  EXPECT_FALSE(b.control.feed_permitted());
  EXPECT_GT(b.ticks_until_at_speed(3000), 200);
}

TEST(SpindleControl, EveryCauseStopsItImmediateOnesAtOnceOthersOnTheRamp) {
  for (const SpindleStopCause cause : kAllCauses) {
    SCOPED_TRACE(to_string(cause));
    SpindleBench b;
    ASSERT_EQ(b.control.start(SpindleDirection::forward, 2000.0), SpindleResult::ok);
    ASSERT_GT(b.ticks_until_at_speed(3000), 0);
    b.control.stop(cause);
    EXPECT_FALSE(b.control.commanded_on());
    EXPECT_EQ(b.control.last_stop_cause(), cause);
    EXPECT_TRUE(b.control.feed_permitted());
    const SpindleOutputs first = b.tick();
    if (kSpindleStopIsImmediate[static_cast<std::size_t>(cause)]) {
      EXPECT_FALSE(first.enable);
      EXPECT_EQ(first.command_rpm, 0.0);
      EXPECT_EQ(first.dac_code, 2048);
    } else {
      EXPECT_TRUE(first.enable) << "a controlled stop brakes under the drive's control";
      EXPECT_NEAR(first.command_rpm, 2000.0 - b.control.params().accel_rpm_s * kSpindleTickS, 1e-9);
    }
    int disabled_at = first.enable ? -1 : 1;
    for (int i = 2; i <= 5000; ++i) {
      const SpindleOutputs out = b.tick();
      if (disabled_at < 0 && !out.enable) disabled_at = i;
      if (disabled_at > 0) {
        EXPECT_FALSE(out.enable) << "enabled again at tick " << i;
      }
    }
    ASSERT_GT(disabled_at, 0);
    EXPECT_LE(std::fabs(b.spindle.rpm), 30.0);
  }
}

TEST(SpindleControl, AnEstopDuringAControlledStopCutsTheEnableAtOnce) {
  SpindleBench b;
  ASSERT_EQ(b.control.start(SpindleDirection::forward, 6000.0), SpindleResult::ok);
  ASSERT_GT(b.ticks_until_at_speed(3000), 0);
  b.control.stop(SpindleStopCause::program_end);
  for (int i = 0; i < 100; ++i) EXPECT_TRUE(b.tick().enable);
  b.control.set_inhibit(true, SpindleStopCause::estop);
  const SpindleOutputs out = b.tick();
  EXPECT_FALSE(out.enable);
  EXPECT_EQ(out.command_rpm, 0.0);
  EXPECT_EQ(b.control.last_stop_cause(), SpindleStopCause::estop);
}

TEST(SpindleControl, ClearingTheCauseNeverStartsItAgain) {
  for (const SpindleStopCause cause : kAllCauses) {
    SCOPED_TRACE(to_string(cause));
    SpindleBench b;
    ASSERT_EQ(b.control.start(SpindleDirection::reverse, 1500.0), SpindleResult::ok);
    ASSERT_GT(b.ticks_until_at_speed(3000), 0);
    b.control.set_inhibit(true, cause);
    for (int i = 0; i < 10; ++i) b.tick();
    EXPECT_EQ(b.control.start(SpindleDirection::forward, 1000.0), SpindleResult::inhibited);
    b.control.set_inhibit(false, cause);  // the fault cleared, the e-stop released, the host back
    for (int i = 0; i < 3000; ++i) {
      const SpindleOutputs out = b.tick();
      EXPECT_FALSE(b.control.commanded_on());
      EXPECT_LE(std::fabs(out.command_rpm), 1500.0);
      EXPECT_TRUE(out.command_rpm == 0.0 || !kSpindleStopIsImmediate[static_cast<std::size_t>(cause)]);
    }
    EXPECT_FALSE(b.control.outputs().enable);
    EXPECT_EQ(b.control.starts(), 1u);
    // Only a new start turns it.
    ASSERT_EQ(b.control.start(SpindleDirection::forward, 1000.0), SpindleResult::ok);
    EXPECT_TRUE(b.tick().enable);
  }
}

TEST(SpindleControl, ReversingRampsThroughZeroAndFlipsTheDirectionThere) {
  SpindleBench b;
  ASSERT_EQ(b.control.start(SpindleDirection::forward, 1000.0), SpindleResult::ok);
  ASSERT_GT(b.ticks_until_at_speed(3000), 0);
  ASSERT_EQ(b.control.start(SpindleDirection::reverse, 1000.0), SpindleResult::ok);
  double last = 1000.0;
  for (int i = 0; i < 500; ++i) {
    const SpindleOutputs out = b.tick();
    EXPECT_LE(out.command_rpm, last);
    EXPECT_EQ(out.reverse, out.command_rpm < 0.0 || out.command_rpm == 0.0);
    EXPECT_TRUE(out.enable);
    last = out.command_rpm;
  }
  EXPECT_EQ(last, -1000.0);
  EXPECT_LT(b.control.outputs().dac_code, 2048);
}

TEST(SpindleControl, BadCommandsAreRefusedAndChangeNothing) {
  SpindleBench b;
  EXPECT_EQ(b.control.set_speed(1000.0), SpindleResult::not_running);
  for (const double rpm : std::array{0.0, -10.0, 12'001.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    EXPECT_EQ(b.control.start(SpindleDirection::forward, rpm), SpindleResult::bad_speed) << rpm;
  }
  EXPECT_FALSE(b.control.commanded_on());
  EXPECT_EQ(b.control.starts(), 0u);
  ASSERT_EQ(b.control.start(SpindleDirection::forward, 1000.0), SpindleResult::ok);
  EXPECT_EQ(b.control.set_speed(-5.0), SpindleResult::bad_speed);
  EXPECT_EQ(b.control.target_rpm(), 1000.0);
}

TEST(SpindleControl, ParametersChangeOnlyAtRestAndOnlyWhenValid) {
  SpindleBench b;
  SpindleParams p = b.control.params();
  p.max_rpm = 8000.0;
  ASSERT_EQ(b.control.start(SpindleDirection::forward, 1000.0), SpindleResult::ok);
  b.tick();
  EXPECT_EQ(b.control.set_params(p), SpindleResult::busy);
  b.control.stop(SpindleStopCause::command);
  for (int i = 0; i < 5000; ++i) b.tick();
  ASSERT_FALSE(b.control.active());
  SpindleParams bad = p;
  bad.accel_rpm_s = 7000.0;  // above the drive's current limit
  EXPECT_EQ(b.control.set_params(bad), SpindleResult::invalid);
  EXPECT_EQ(validate(bad).member, &bad.accel_rpm_s);
  EXPECT_EQ(b.control.params().max_rpm, 12'000.0);
  ASSERT_EQ(b.control.set_params(p), SpindleResult::ok);
  EXPECT_EQ(b.control.start(SpindleDirection::forward, 9000.0), SpindleResult::bad_speed);
  EXPECT_FALSE(b.control.commanded_on()) << "a parameter change does not start it";
}

TEST(SpindleControl, EachParameterIsCheckedAgainstItsOwnRange) {
  const SpindleParams ok{};
  EXPECT_TRUE(validate(ok).ok);
  // validate() names the member of the object it was given: compare in place.
  SpindleParams p{};
  p.standstill_rpm = 0.0;
  EXPECT_EQ(validate(p).member, &p.standstill_rpm);
  p = {};
  p.at_speed_ticks = 0;
  EXPECT_EQ(validate(p).member, &p.at_speed_ticks);
  p = {};
  p.at_speed_fraction = 0.6;
  EXPECT_EQ(validate(p).member, &p.at_speed_fraction);
  p = {};
  p.at_speed_floor_rpm = -1.0;
  EXPECT_EQ(validate(p).member, &p.at_speed_floor_rpm);
  p = {};
  p.max_rpm = 12'500.0;
  EXPECT_EQ(validate(p).member, &p.max_rpm);
}

// Random sequences of every event: the spindle is commanded on only right
// after an accepted start(), and its enable rises only while commanded on.
TEST(SpindleControl, OverRandomEventsNothingButStartTurnsItOn) {
  std::mt19937 rng(20261128);
  SpindleBench b;
  bool inhibited = false;
  int accepted_starts = 0;
  int enable_rises = 0;
  for (int step = 0; step < 100'000; ++step) {
    const bool on_before = b.control.commanded_on();
    const bool enable_before = b.control.outputs().enable;
    bool accepted_start = false;
    const SpindleStopCause cause = kAllCauses[rng() % kAllCauses.size()];
    switch (rng() % 8) {
      case 0:
        accepted_start = b.control.start(rng() % 2 ? SpindleDirection::forward : SpindleDirection::reverse,
                                         100.0 + static_cast<double>(rng() % 8000)) == SpindleResult::ok;
        accepted_starts += accepted_start ? 1 : 0;
        break;
      case 1: (void)b.control.set_speed(static_cast<double>(rng() % 9000)); break;
      case 2: b.control.stop(cause); break;
      case 3:
        inhibited = !inhibited;
        b.control.set_inhibit(inhibited, cause);
        break;
      case 4: (void)b.control.set_params(SpindleParams{}); break;
      default: {
        b.tick();
        const bool enable_after = b.control.outputs().enable;
        if (enable_after && !enable_before) {
          ++enable_rises;
          EXPECT_TRUE(b.control.commanded_on()) << "step " << step;
        }
        if (!b.control.commanded_on()) {
          EXPECT_LE(std::fabs(b.control.outputs().command_rpm), 8100.0);
        }
        break;
      }
    }
    if (b.control.commanded_on() && !on_before) {
      ASSERT_TRUE(accepted_start) << "turned on by something other than start(), step " << step;
    }
    if (inhibited) {
      ASSERT_FALSE(b.control.commanded_on()) << "on while inhibited, step " << step;
    }
  }
  EXPECT_GT(accepted_starts, 1000);  // the sequence did exercise starts
  EXPECT_GT(enable_rises, 100);
  EXPECT_EQ(b.control.starts(), static_cast<std::uint32_t>(accepted_starts));
}

TEST(SpindleSpeed, MMethodGivesRpmAndTheDacSaturates) {
  EXPECT_DOUBLE_EQ(spindle_rpm(4096, 10'000'000), 60.0);   // a revolution in one second
  EXPECT_DOUBLE_EQ(spindle_rpm(-683, 10'000), -683.0 * 60.0 / 4096.0 / 0.001);
  EXPECT_EQ(spindle_rpm(5, 0), 0.0);
  EXPECT_EQ(spindle_dac_code(0.0), 2048);
  EXPECT_EQ(spindle_dac_code(20'000.0), 4095);
  EXPECT_EQ(spindle_dac_code(-20'000.0), 0);
  EXPECT_EQ(spindle_dac_code(std::nan("")), 2048);
}

}  // namespace
}  // namespace tnv::fw
