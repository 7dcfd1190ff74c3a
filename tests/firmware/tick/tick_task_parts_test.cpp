// TickTask's parts on their own (firmware/tick: HomingSequence,
// PathShapers, ProgramFeedOverride), through their narrow interfaces; the
// task as a whole is tested by tick_task_test.cpp and the HIL tests.
#include <gtest/gtest.h>

#include "firmware/motion/motion_interpolator.hpp"
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

}  // namespace
}  // namespace tnv::test
