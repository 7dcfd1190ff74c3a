// TickTask's parts on their own (firmware/tick: HomingSequence,
// PathShapers, ProgramFeedOverride, AxisExcitations, AxisLoop), through their narrow
// interfaces; the task as a whole is tested by tick_task_test.cpp and the
// HIL tests.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>

#include "firmware/motion/motion_interpolator.hpp"
#include "firmware/io/dac_code.hpp"
#include "firmware/tick/axis_excitations.hpp"
#include "firmware/tick/axis_loop.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/tick/homing_sequence.hpp"
#include "firmware/tick/path_shapers.hpp"
#include "firmware/tick/program_feed_override.hpp"
#include "firmware/tick/tick_record.hpp"
#include "firmware/timing/m_method_speed.hpp"

namespace tnv::test {
namespace {

constexpr double kTickS = 1e-3;

// Each axis' switch 2 mm below where it starts, its index 0.5 mm past the
// switch's release: the sequence's cycles run against it tick by tick.
struct HomingBench {
  fw::FirmwareConfig config = fw::default_firmware_config();
  fw::HomingSequence::HoldPoints hold{};
  std::array<double, hal::kAxisCount> start_mm{};
  std::array<std::size_t, hal::kAxisCount> order{};  // the axes in the order they homed
  std::size_t homed_count = 0;

  HomingBench() {
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      start_mm[i] = 10.0 * static_cast<double>(i + 1);
      hold[i] = {start_mm[i], 0.0};
      config.axis[i].homing.search_positive = false;
    }
  }
  // Ticks until the command is over; false when it never ends.
  bool run(fw::HomingSequence& seq) {
    for (int tick = 0; tick < 200000; ++tick) {
      const std::size_t a = seq.axis();
      const double at_mm = hold[a].position_mm;
      const bool switch_on = at_mm < start_mm[a] - 2.0;
      const std::uint8_t edges = at_mm > start_mm[a] - 1.5 && passed_switch ? 1 : 0;
      passed_switch = passed_switch || switch_on;
      const fw::HomingStep step = seq.step(switch_on, edges);
      hold[a] = {step.next.position_mm, step.next.speed_mm_s};
      if (seq.running()) continue;
      order[homed_count++] = a;
      hold[a] = {step.next.position_mm, 0.0};
      passed_switch = false;
      if (!seq.next_axis(config, hold, kTickS)) return true;
    }
    return false;
  }
  bool passed_switch = false;
};

TEST(HomingSequence, HomesTheNamedAxesOneAfterTheOtherInHomingOrder) {
  fw::HomingSequence seq;
  HomingBench bench;
  seq.begin(hal::kEveryAxis, bench.config, bench.hold, kTickS);
  EXPECT_TRUE(seq.running());
  const std::size_t first = hal::index(hal::kHomingOrder[0]);
  EXPECT_EQ(seq.axis(), first);
  EXPECT_EQ(seq.result(first), fw::HomingResult::running);
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) EXPECT_EQ(seq.soft_limits_off(i), i == first);
  ASSERT_TRUE(bench.run(seq));
  const fw::HomingCycle last = seq.finish();
  EXPECT_EQ(last.phase(), fw::HomingPhase::done);
  EXPECT_FALSE(seq.running());
  ASSERT_EQ(bench.homed_count, hal::kAxisCount);
  for (std::size_t k = 0; k < hal::kAxisCount; ++k) {
    EXPECT_EQ(bench.order[k], hal::index(hal::kHomingOrder[k]));
    EXPECT_TRUE(seq.homed(k));
    EXPECT_EQ(seq.result(k), fw::HomingResult::homed);
    EXPECT_FALSE(seq.soft_limits_off(k));
  }
  seq.unhome(first);
  EXPECT_FALSE(seq.homed(first));
  seq.unhome_all();
  for (std::size_t k = 0; k < hal::kAxisCount; ++k) EXPECT_FALSE(seq.homed(k));
}

TEST(HomingSequence, AStoppedCycleEndsTheCommandAndAServoOffCancelsIt) {
  HomingBench bench;
  const std::size_t first = hal::index(hal::kHomingOrder[0]);
  {
    fw::HomingSequence seq;
    seq.begin(hal::kEveryAxis, bench.config, bench.hold, kTickS);
    for (int i = 0; i < 50; ++i) (void)seq.step(false, 0);  // searching
    seq.abort();
    int ticks = 0;
    while (seq.running() && ++ticks < 100000) (void)seq.step(false, 0);
    ASSERT_FALSE(seq.running());
    EXPECT_FALSE(seq.next_axis(bench.config, bench.hold, kTickS)) << "no other axis starts";
    EXPECT_EQ(seq.finish().result(), fw::HomingResult::aborted);
    EXPECT_EQ(seq.result(first), fw::HomingResult::aborted);
    EXPECT_FALSE(seq.homed(first));
  }
  {
    fw::HomingSequence seq;
    seq.begin(hal::kEveryAxis, bench.config, bench.hold, kTickS);
    (void)seq.step(false, 0);
    seq.cancel();
    EXPECT_FALSE(seq.running());
    EXPECT_EQ(seq.result(first), fw::HomingResult::aborted);
    EXPECT_FALSE(seq.soft_limits_off(first));
  }
}

fw::ShaperDesign design_at(double freq_hz) {
  fw::ShaperSpec spec;
  spec.mode.freq_hz = freq_hz;
  spec.mode.zeta = 0.05;
  return fw::design_shaper(spec, kTickS);
}

TEST(PathShapers, OffTheReferencePassesBitForBitAndOnItIsShapedAfterTheHandOver) {
  fw::PathShapers shapers;
  const fw::AxisSample now{0.1 + 0.2, 1.0 / 3.0};
  const fw::AxisSample next{0.3 + 1e-17, 2.0 / 3.0};
  const fw::PathShapers::Pair off = shapers.shape(0, now, next);
  EXPECT_EQ(off.now.position_mm, now.position_mm);
  EXPECT_EQ(off.now.speed_mm_s, now.speed_mm_s);
  EXPECT_EQ(off.next.position_mm, next.position_mm);
  EXPECT_TRUE(shapers.settled());

  EXPECT_FALSE(shapers.enable(0, true)) << "never configured";
  ASSERT_TRUE(shapers.configure(0, design_at(25.0)));
  ASSERT_TRUE(shapers.enable(0, true));
  EXPECT_FALSE(shapers.active(0)) << "planned, not handed over yet";
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) shapers.reset(i, {0.0, 0.0});
  shapers.forward_when_quiet(true);  // servo off: handed over now
  (void)shapers.shape(0, {0.0, 0.0}, {0.0, 0.0});
  EXPECT_TRUE(shapers.active(0));
  EXPECT_GT(shapers.shaper(0).delay_samples(), 0.0);
  EXPECT_EQ(shapers.design(0).period_s, kTickS);
  // A step in the source comes out gradually: the first shaped sample is short of it.
  const fw::PathShapers::Pair shaped = shapers.shape(0, {0.0, 0.0}, {1.0, 0.0});
  EXPECT_LT(shaped.next.position_mm, 1.0);
  EXPECT_FALSE(shapers.settled());
}

TEST(ProgramFeedOverride, TheOperatorsOverrideGoesToTheMotionCoreAndEachProgramStartsAtOne) {
  fw::ProgramFeedOverride feed;
  fw::motion::MotionInterpolator motion;
  ASSERT_FALSE(feed.force_loop().enabled()) << "the force loop is off by default";
  EXPECT_TRUE(feed.set_operator_override(0.5, motion));
  EXPECT_EQ(feed.operator_override(), 0.5);
  EXPECT_EQ(motion.feed_override(), 0.5);
  fw::TickRecord record;
  record.arsc_force_ref_n = 7.0;
  feed.tick(true, 1.0, motion, record);
  EXPECT_EQ(record.feed_override, 0.5);
  EXPECT_EQ(record.arsc_force_ref_n, 0.0) << "no loop running: no f*";
  feed.program_started();
  EXPECT_EQ(feed.operator_override(), 1.0);
}

TEST(AxisExcitations, EachAxisRunsItsOwnCountedFromItsStartAndLeavingHoldingCancelsIt) {
  using Kind = fw::AxisExcitations::HoldStep::Kind;
  fw::AxisExcitations e;
  EXPECT_FALSE(e.running());
  EXPECT_EQ(e.hold_step(0, true).kind, Kind::none);

  fw::ExcitationSpec ramp;  // open loop; it ends when the axis has moved 12 counts from its start
  ramp.kind = fw::ExcitationKind::ramp;
  e.start(0, ramp, 100);
  EXPECT_TRUE(e.running());
  EXPECT_TRUE(e.running(0));
  EXPECT_FALSE(e.running(1));
  EXPECT_TRUE(e.open_loop(0));
  EXPECT_EQ(e.hold_step(0, true).kind, Kind::follow_table);
  EXPECT_EQ(e.hold_step(1, true).kind, Kind::none);
  fw::ExcitationGenerator alone;  // the same excitation, counted from 0
  alone.start(ramp);
  std::array<double, 8> command_mm_s{};
  for (std::int64_t k = 0; k < 8; ++k) {
    command_mm_s[static_cast<std::size_t>(k)] = e.next(0, 100 + 2 * k);
    EXPECT_DOUBLE_EQ(command_mm_s[static_cast<std::size_t>(k)], alone.next(2 * k)) << k;
  }
  EXPECT_GT(command_mm_s[1], 0.0) << "ramping while the axis has moved 2 counts";
  EXPECT_EQ(command_mm_s[7], 0.0) << "14 counts moved: the ramp has ended (settling)";
  EXPECT_TRUE(e.running(0)) << "settling is part of it";

  fw::ExcitationSpec sweep;
  sweep.kind = fw::ExcitationKind::sweep;
  sweep.level_mm_s = 1.0;
  sweep.duration_s = 1.0;
  sweep.carrier_mm_s = 5.0;
  e.start(1, sweep, -40);
  EXPECT_FALSE(e.open_loop(1)) << "closed loop: added to the controller's command";
  EXPECT_EQ(e.hold_step(1, true).kind, Kind::carrier);
  sweep.carrier_mm_s = 0.0;
  fw::AxisExcitations at_rest;
  at_rest.start(1, sweep, 0);
  EXPECT_EQ(at_rest.hold_step(1, true).kind, Kind::none) << "no carrier: the hold point stays";
  EXPECT_TRUE(at_rest.running(1));

  EXPECT_EQ(e.hold_step(0, false).kind, Kind::none);
  EXPECT_FALSE(e.running(0)) << "leaving holding cancels it";
  EXPECT_TRUE(e.running(1)) << "the other axis' goes on";
}

TEST(AxisExcitations, ACarriersTravelMustEndInsideTheSoftLimits) {
  fw::AxisLimits limits;
  limits.position_min_mm = -10.0;
  limits.position_max_mm = 10.0;
  fw::ExcitationSpec spec;
  spec.kind = fw::ExcitationKind::sweep;
  spec.duration_s = 1.0;
  spec.carrier_mm_s = 5.0;
  EXPECT_TRUE(fw::AxisExcitations::carrier_travel_fits(limits, 5.0, spec));  // ends at 10
  EXPECT_FALSE(fw::AxisExcitations::carrier_travel_fits(limits, 5.5, spec));
  spec.carrier_mm_s = -5.0;
  EXPECT_TRUE(fw::AxisExcitations::carrier_travel_fits(limits, -5.0, spec));
  EXPECT_FALSE(fw::AxisExcitations::carrier_travel_fits(limits, -5.5, spec));
  spec.carrier_mm_s = 0.0;
  EXPECT_TRUE(fw::AxisExcitations::carrier_travel_fits(limits, 50.0, spec)) << "no carrier: no travel";
}

// One tick of an AxisLoop on its own: the count since the last snapshot,
// measure() from it, control() against a reference, output().
struct AxisLoopBench {
  fw::FirmwareConfig config = fw::default_firmware_config();
  fw::AxisConfig& axis = config.axis[0];
  fw::AxisLimits& limits = config.supervisor.axis[0];
  fw::AxisLoop loop{axis, 16};
  fw::AxisExcitations excite{};
  fw::AxisTickRecord r{};
  fw::AxisCheckInput check{};
  static constexpr std::uint32_t kPeriodClocks = 10'000;  // 1 ms

  // raw: this snapshot's latched count; ref_mm: the reference held there.
  bool tick(std::uint32_t raw, double ref_mm, bool on, double origin_mm = 0.0) {
    loop.count(raw, axis.count_mm, kPeriodClocks);
    loop.measure(origin_mm, axis, limits, true, 0, true, r);
    r.reference_mm = ref_mm;
    r.reference_speed_mm_s = 0.0;
    const bool ended = loop.control(on, axis, {ref_mm, 0.0}, kTickS, excite, 0, r, check);
    fw::AxisLoop::output(on, axis.dac, r);
    return ended;
  }
};

TEST(AxisLoop, MeasuresFromTheCountControlsTowardTheReferenceAndWritesTheDacCode) {
  AxisLoopBench b;
  b.axis.observer.enabled = false;
  b.loop.restart_count(1000);
  b.tick(1100, 0.0, false, 5.0);
  EXPECT_EQ(b.loop.counts(), 100);
  EXPECT_DOUBLE_EQ(b.r.position_mm, 5.0 + 100.0 * b.axis.count_mm);
  EXPECT_DOUBLE_EQ(b.r.speed_mm_s, fw::m_method_speed_mm_s(100, b.axis.count_mm, AxisLoopBench::kPeriodClocks));
  EXPECT_EQ(b.r.command_mm_s, 0.0) << "servo off: no command";
  EXPECT_EQ(b.r.dac_code, b.axis.dac.mid_code());
  EXPECT_FALSE(b.r.enabled);
  EXPECT_DOUBLE_EQ(b.check.position_mm, b.r.position_mm);

  b.tick(1100, b.r.position_mm + 1.0, true, 5.0);  // the reference 1 mm ahead of the axis
  EXPECT_GT(b.r.command_mm_s, 0.0);
  EXPECT_EQ(b.check.command_mm_s, b.r.command_mm_s);
  EXPECT_DOUBLE_EQ(b.check.reference_mm, b.r.reference_mm);
  EXPECT_TRUE(b.r.enabled);
  EXPECT_EQ(b.r.dac_code, fw::speed_to_dac_code(b.r.command_mm_s, b.axis.dac));
  EXPECT_GT(b.r.dac_code, b.axis.dac.mid_code());

  b.tick(1100, b.r.position_mm - 1.0, true, 5.0);  // and 1 mm behind
  EXPECT_LT(b.r.command_mm_s, 0.0);
}

TEST(AxisLoop, ItsStallMonitorCountsDrivenTicksWithoutACountAndTheCheckInputCarriesThem) {
  AxisLoopBench b;
  b.loop.restart_count(0);
  const double far_mm = 10.0;  // a command well above the stall level
  b.tick(0, far_mm, true);
  ASSERT_GE(std::fabs(b.r.command_mm_s), b.limits.stall.command_mm_s);
  for (std::uint32_t k = 1; k <= 3; ++k) {
    b.tick(0, far_mm, true);
    EXPECT_EQ(b.check.stalled_ticks, k) << "the count stands while driven";
    EXPECT_EQ(b.check.stall_command_mm_s, b.loop.stall().applied_command_mm_s());
  }
  b.tick(5, far_mm, true);
  EXPECT_EQ(b.check.stalled_ticks, 0u) << "a count: moved";
}

TEST(AxisLoop, AnOpenLoopExcitationReplacesTheControllerAndItsEndIsReported) {
  AxisLoopBench b;
  b.loop.restart_count(0);
  fw::ExcitationSpec ramp;  // open loop; it ends some ticks after the axis has moved 12 counts
  ramp.kind = fw::ExcitationKind::ramp;
  b.excite.start(0, ramp, 0);
  fw::ExcitationGenerator alone;
  alone.start(ramp);
  bool ended = false;
  std::uint32_t raw = 0;
  for (int k = 0; k < 100000 && !ended; ++k) {
    const double expected_mm_s = alone.next(raw);
    ended = b.tick(raw, 100.0, true);  // the reference is ignored while open loop
    EXPECT_EQ(b.r.command_mm_s, expected_mm_s) << k;
    EXPECT_EQ(b.r.excitation_mm_s, expected_mm_s) << k;
    raw += 2;
  }
  EXPECT_TRUE(ended);
  EXPECT_FALSE(b.excite.running(0));
  EXPECT_FALSE(b.tick(raw, 100.0, true)) << "reported once";
}

TEST(AxisLoop, ANewConfigSelectsTheControllerAndTakesNewGains) {
  AxisLoopBench b;
  fw::AxisConfig to = b.axis;
  to.controller = to.controller == fw::ControllerKind::pid ? fw::ControllerKind::rdvsc : fw::ControllerKind::pid;
  to.pid.kp *= 2.0;
  to.sliding.gamma *= 0.5;
  b.loop.apply(b.axis, to, false, 0.0);
  EXPECT_EQ(b.loop.kind(), to.controller);
  EXPECT_EQ(b.loop.pid_params().kp, to.pid.kp);
  EXPECT_EQ(b.loop.sliding_params().gamma, to.sliding.gamma);
  b.loop.select(fw::ControllerKind::dvsc);
  EXPECT_EQ(b.loop.kind(), fw::ControllerKind::dvsc);
}

}  // namespace
}  // namespace tnv::test
