// The force loop as a feed-override source (arsc_feed_source.hpp) driving
// the real motion core on a program of short segments, with a cut
// simulated from the reference: f follows G x path feed with the cut's lag.
// The override must stay in its range, the planner must keep its limits
// however the override moves, the loop samples at its own rate, pauses
// when the path does not run and regulates the force when it does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "firmware/adaptive/arsc/arsc_feed_source.hpp"
#include "tests/firmware/motion/motion_run.hpp"

namespace tnv::fw::arsc {
namespace {

using motion::MotionInterpolator;
using motion::PlanePoint;
using motion::Segment;

constexpr double kFeedMmS = 60.0;

// 1 mm pieces along X, a tangent arc turning 45 deg, 1 mm pieces at 45 deg.
std::vector<Segment> cutting_pass() {
  std::vector<Segment> p;
  for (int i = 1; i <= 150; ++i) p.push_back(motion::line_to({-200.0 + i, 0.0}, kFeedMmS));
  const double r = 20.0, c = std::cos(std::numbers::pi / 4.0), s = std::sin(std::numbers::pi / 4.0);
  p.push_back(motion::arc_to(false, {-50.0 + r * s, r - r * c}, {-50.0, r}, kFeedMmS));
  for (int i = 1; i <= 250; ++i) p.push_back(motion::line_to({-50.0 + r * s + i * c, r - r * c + i * s}, kFeedMmS));
  return p;
}

ArscSourceParams on_params() {
  ArscSourceParams p;
  p.enabled = true;
  p.soft_start_s = 0.2;
  return p;
}

// The motion core, the source and a simulated cut, one tick at a time.
struct Cut {
  MotionInterpolator motion;
  ArscFeedSource source;
  std::vector<Segment> program = cutting_pass();
  std::size_t next = 0;
  double force_n = 0.0;
  double gain_n_per_mm_s = 3.0;  // the cut's G per mm/s of path feed (the test changes it)
  double noise_n = 0.0;          // +- this, pseudo-random, on the measured force
  double operator_override = 1.0;
  std::uint32_t lcg = 7;
  motion::test::MotionRun run;   // the commanded reference, for the limits
  double override_min_seen = 2.0, override_max_seen = -1.0;
  PlanePoint pos{-200.0, 0.0}, speed{0.0, 0.0};

  // The planner's limits of the machine study (arsc_tick_study.hpp): 2000 mm/s^2 and 200,000 mm/s^3.
  static motion::MotionLimits limits() {
    motion::MotionLimits l;
    for (motion::AxisLimits& a : l.axis) {
      a.accel_mm_s2 = 2000.0;
      a.jerk_mm_s3 = 200000.0;
    }
    return l;
  }
  explicit Cut(const ArscSourceParams& params) {
    EXPECT_STREQ(motion.configure(limits(), pos), "");
    EXPECT_TRUE(source.configure(params).ok);
    source.start({pos[0], pos[1]});  // the force loop is the XY plane's
  }
  void tick() {
    while (next < program.size() && motion.free_slots() > 0) ASSERT_EQ(motion.push(program[next++]), motion::SegmentRefusal::none);
    if (next == program.size()) motion.end_program();
    lcg = lcg * 1664525u + 1013904223u;
    const double noise = noise_n * (2.0 * static_cast<double>(lcg >> 8) / 16777216.0 - 1.0);
    ArscFeedInput in;
    in.force_n = std::max(force_n + noise, 0.0);
    in.position_mm = {pos[0], pos[1]};
    in.speed_mm_s = {speed[0], speed[1]};
    in.programmed_feed_mm_s = motion.running_feed_mm_s();
    in.operator_override = operator_override;
    const double ratio = source.tick(in);
    ASSERT_TRUE(motion.set_feed_override(ratio)) << ratio;
    override_min_seen = std::min(override_min_seen, ratio);
    override_max_seen = std::max(override_max_seen, ratio);
    const motion::MotionReference r = motion.tick();
    // The table follows the reference exactly; the cut answers its path feed with T_f = 0.2 s.
    pos = {r.axis[0].position_mm, r.axis[1].position_mm};
    speed = {r.axis[0].speed_mm_s, r.axis[1].speed_mm_s};
    const double a = std::exp(-1e-3 / 0.2);
    force_n = a * force_n + (1.0 - a) * gain_n_per_mm_s * std::hypot(speed[0], speed[1]);
    run.position_mm.push_back(pos);
  }
};

TEST(ArscFeedSource, RegulatesTheForceOnALineAndThroughAnArc) {
  Cut cut(on_params());
  double worst_pct = 0.0;
  for (int k = 0; k < 6000; ++k) {
    cut.gain_n_per_mm_s = k < 3000 ? 3.0 : 6.0;  // the depth doubles at 3 s
    cut.tick();
    if (k > 1000 && (k < 3000 || k > 4000)) worst_pct = std::max(worst_pct, std::fabs(cut.force_n - 150.0) / 1.5);
  }
  EXPECT_LT(worst_pct, 2.0) << "force error away from the start and the depth step, % of f*";
  EXPECT_GT(cut.pos[1], 10.0) << "the path must have turned through the arc, mm of Y";
  EXPECT_EQ(cut.source.status().state, ArscSourceState::cutting);
  EXPECT_NEAR(cut.source.status().cutting_gain_n_per_mm_s, 6.0, 0.3) << "estimate after the depth step";
}

TEST(ArscFeedSource, TheOverrideStaysInItsRangeAndThePlannerKeepsItsLimits) {
  for (const std::uint32_t period : {1u, 7u, 150u}) {
    ArscSourceParams p = on_params();
    p.period_ticks = period;
    p.override_min = 0.3;
    p.override_max = 1.2;
    p.pole_re_rad_s = -60.0;
    Cut cut(p);
    cut.noise_n = 20.0;
    for (int k = 0; k < 8000; ++k) {
      // The cut's gain jumps 4x and back every 0.7 s: the loop is driven into both ends of its range.
      cut.gain_n_per_mm_s = (k / 700) % 2 == 0 ? 1.5 : 6.0;
      cut.tick();
      const double o = cut.motion.feed_override();
      ASSERT_GE(o, 0.3) << "tick " << k;
      ASSERT_LE(o, 1.2) << "tick " << k;
    }
    motion::test::score_limits(cut.run, cut.motion.limits());
    SCOPED_TRACE(testing::Message() << "period " << period << " ticks");
    EXPECT_NEAR(cut.override_min_seen, 0.3, 1e-12) << "the loop must reach the bottom of its range";
    EXPECT_NEAR(cut.override_max_seen, 1.2, 1e-12) << "and the top";
    EXPECT_GT(cut.source.status().clamped_samples, 0u);
    EXPECT_LE(cut.run.accel_ratio_max, 1.0 + 1e-6) << "commanded acceleration over the axis limit";
    EXPECT_LE(cut.run.jerk_ratio_max, 1.0 + 1e-6) << "commanded jerk over the axis limit";
    EXPECT_EQ(cut.motion.stats().follower.brake_shortfalls, 0u);
    EXPECT_EQ(cut.motion.stats().follower.guard_failures, 0u);
  }
}

TEST(ArscFeedSource, SamplesEveryPeriodAndHoldsTheFeedCommandBetween) {
  ArscSourceParams p = on_params();
  p.period_ticks = 10;
  Cut cut(p);
  double command = -1.0;
  for (int k = 0; k < 500; ++k) {
    cut.tick();
    const ArscSourceStatus& s = cut.source.status();
    EXPECT_EQ(s.samples, static_cast<std::uint32_t>(k / 10 + 1)) << "tick " << k;
    if (k % 10 != 0) {
      EXPECT_EQ(s.command_mm_s, command) << "tick " << k << ": changed between samples";
    }
    command = s.command_mm_s;
  }
}

TEST(ArscFeedSource, TheOperatorOverrideScalesTheRangeAndZeroHoldsThePath) {
  ArscSourceParams p = on_params();
  p.override_max = 1.5;
  Cut cut(p);
  cut.gain_n_per_mm_s = 0.5;  // a light cut: the loop wants more feed than it may have
  cut.operator_override = 0.5;
  for (int k = 0; k < 1500; ++k) cut.tick();
  EXPECT_NEAR(cut.motion.feed_override(), 0.75, 1e-12) << "0.5 x override_max";
  cut.operator_override = 0.0;
  for (int k = 0; k < 1500; ++k) cut.tick();
  EXPECT_EQ(cut.motion.feed_override(), 0.0);
  EXPECT_EQ(cut.motion.path_speed_mm_s(), 0.0) << "the path point must rest";
}

TEST(ArscFeedSource, DoesNotSampleWhileThePathDoesNotRunAndRestartsSoftly) {
  Cut cut(on_params());
  for (int k = 0; k < 1500; ++k) cut.tick();
  EXPECT_NEAR(cut.source.status().force_ref_n, 150.0, 1e-9);
  cut.motion.hold();
  for (int k = 0; k < 1000; ++k) cut.tick();
  const std::uint32_t samples = cut.source.status().samples;
  EXPECT_EQ(cut.source.status().state, ArscSourceState::paused);
  for (int k = 0; k < 100; ++k) cut.tick();
  EXPECT_EQ(cut.source.status().samples, samples) << "sampled while the path was held";
  cut.motion.resume();
  cut.tick();
  EXPECT_EQ(cut.source.status().state, ArscSourceState::cutting);
  EXPECT_LT(cut.source.status().force_ref_n, 1.0) << "f* starts its soft start again";
  for (int k = 0; k < 1500; ++k) cut.tick();
  EXPECT_NEAR(cut.force_n, 150.0, 3.0) << "back on f* after the resume, N";
}

TEST(ArscFeedSource, BadParametersAreRefusedAndTheSourceKeepsItsOwn) {
  ArscFeedSource source;
  ASSERT_TRUE(source.configure(on_params()).ok);
  const auto refused = [&source](auto change) {
    ArscSourceParams p = on_params();
    change(p);
    const ParamCheck c = source.configure(p);
    return c.ok ? "" : c.field;
  };
  EXPECT_STREQ(refused([](ArscSourceParams& p) { p.period_ticks = 0; }), "period_ticks");
  EXPECT_STREQ(refused([](ArscSourceParams& p) { p.period_ticks = 501; }), "period_ticks");
  EXPECT_STREQ(refused([](ArscSourceParams& p) { p.pole_re_rad_s = 0.0; }), "pole_re_rad_s");
  EXPECT_STREQ(refused([](ArscSourceParams& p) { p.pole_im_rad_s = -1.0; }), "pole_im_rad_s");
  EXPECT_STREQ(refused([](ArscSourceParams& p) { p.override_max = 1.6; }), "override_max");
  EXPECT_STREQ(refused([](ArscSourceParams& p) { p.override_min = 0.9, p.override_max = 0.8; }), "override_min");
  EXPECT_STREQ(refused([](ArscSourceParams& p) { p.gain_min_ratio = 1.5; }), "gain_min_ratio");
  EXPECT_STREQ(refused([](ArscSourceParams& p) { p.force_time_constant_s = std::nan(""); }), "force_time_constant_s");
  // Poles the loop cannot reach at its model and rate: gains beyond the bound.
  EXPECT_STREQ(refused([](ArscSourceParams& p) { p.pole_re_rad_s = -5000.0; }), "pole_re_rad_s");
  EXPECT_TRUE(source.params().enabled) << "a refused set changes nothing";
  EXPECT_EQ(source.params().period_ticks, 1u);
  EXPECT_EQ(source.status().state, ArscSourceState::waiting);
}

}  // namespace
}  // namespace tnv::fw::arsc
