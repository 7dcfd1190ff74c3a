// TickTask's parts on their own (firmware/tick: HomingSequence,
// PathShapers, ProgramFeedOverride, AxisExcitations), through their narrow
// interfaces; the task as a whole is tested by tick_task_test.cpp and the
// HIL tests.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>

#include "firmware/motion/motion_interpolator.hpp"
#include "firmware/tick/axis_excitations.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/tick/homing_sequence.hpp"
#include "firmware/tick/path_shapers.hpp"
#include "firmware/tick/program_feed_override.hpp"
#include "firmware/tick/tick_record.hpp"

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

}  // namespace
}  // namespace tnv::test
