// A feed override that changes all the time (the force loop's, every tick)
// on programs of short segments: every joint is near, and the limits must
// still hold (docs/motion.md "Feed override").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "tests/firmware/motion/motion_run.hpp"

namespace tnv::fw::motion {
namespace {

using test::MotionRun;
using test::run_program;

// 1 mm pieces of a 200 mm line, a tangent arc, 1 mm pieces of a 45 deg line.
std::vector<Segment> short_pieces(double feed_mm_s) {
  std::vector<Segment> p;
  for (int i = 1; i <= 200; ++i) p.push_back(line_to({-100.0 + i, 0.0}, feed_mm_s));
  const double r = 20.0, c = std::cos(std::numbers::pi / 4.0), s = std::sin(std::numbers::pi / 4.0);
  p.push_back(arc_to(false, {100.0 + r * s, r - r * c}, {100.0, r}, feed_mm_s));
  for (int i = 1; i <= 100; ++i) p.push_back(line_to({100.0 + r * s + i * c, r - r * c + i * s}, feed_mm_s));
  return p;
}

TEST(MotionOverride, AnOverrideJumpingEveryFewTicksOnShortSegmentsKeepsTheLimits) {
  for (const int every : {1, 7, 150}) {
    MotionInterpolator m;
    ASSERT_STREQ(m.configure({}, {-100.0, 0.0}), "");
    std::uint32_t lcg = 12345;
    double lowest = 1.5, highest = 0.0;
    const MotionRun run = run_program(m, short_pieces(60.0), 200000, [&](std::size_t k, MotionInterpolator& mi) {
      if (k % static_cast<std::size_t>(every) != 0) return;
      lcg = lcg * 1664525u + 1013904223u;
      // Mostly 0.2 .. 1.5, now and then a drop to 0 (a feed-hold-like override).
      const double ratio = (lcg >> 28) == 0 ? 0.0 : 0.2 + 1.3 * static_cast<double>(lcg >> 8) / 16777216.0;
      ASSERT_TRUE(mi.set_feed_override(ratio));
      lowest = std::min(lowest, ratio);
      highest = std::max(highest, ratio);
    });
    SCOPED_TRACE(every);
    EXPECT_LT(lowest, 0.3);
    EXPECT_GT(highest, 1.4);
    EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-6) << "commanded acceleration over the axis limit";
    EXPECT_LE(run.jerk_ratio_max, 1.0 + 1e-6) << "commanded jerk over the axis limit";
    EXPECT_EQ(m.stats().follower.brake_shortfalls, 0u) << "the path point braked harder than the limit";
    EXPECT_EQ(m.stats().follower.guard_failures, 0u);
    EXPECT_EQ(m.queued(), 0u) << "the program did not run to its end";
  }
}

// A random program: lines of 0.2 .. 8 mm with corners, tangent arcs, dwells,
// exact stops and a feed of 5 .. 70 mm/s each, in +-200 mm.
std::vector<Segment> random_program(std::uint32_t seed) {
  std::uint32_t g = seed * 7919u;
  const auto rnd = [&g] {
    g = g * 1664525u + 1013904223u;
    return static_cast<double>(g >> 8) / 16777216.0;
  };
  std::vector<Segment> p;
  PlanePoint at{0.0, 0.0};
  double heading = 0.0;
  for (int i = 0; i < 150; ++i) {
    const double feed = std::min(5.0 + 95.0 * rnd(), 70.0);
    const double kind = rnd();
    if (kind < 0.05) {
      p.push_back(dwell_for(0.01 + 0.05 * rnd()));
      continue;
    }
    if (kind < 0.25) {  // tangent arc turning 0.5 .. 1.5 rad either way
      const double r = 2.0 + 20.0 * rnd();
      const double turn = (rnd() < 0.5 ? 1.0 : -1.0) * (0.5 + rnd());
      const double side = turn > 0.0 ? 1.0 : -1.0;
      const PlanePoint c{at[0] - r * std::sin(heading) * side, at[1] + r * std::cos(heading) * side};
      const double a1 = std::atan2(at[1] - c[1], at[0] - c[0]) + turn;
      const PlanePoint e{c[0] + r * std::cos(a1), c[1] + r * std::sin(a1)};
      if (std::fabs(e[0]) > 200.0 || std::fabs(e[1]) > 200.0) continue;
      p.push_back(arc_to(turn < 0.0, e, c, std::min(feed, 60.0)));
      at = e;
      heading += turn;
      continue;
    }
    const double length = 0.2 + 8.0 * rnd() * rnd();
    if (kind < 0.4) heading += (rnd() - 0.5) * 2.0;  // a corner
    const PlanePoint e{at[0] + length * std::cos(heading), at[1] + length * std::sin(heading)};
    if (std::fabs(e[0]) > 200.0 || std::fabs(e[1]) > 200.0) {
      heading += std::numbers::pi;
      continue;
    }
    Segment s = line_to(e, feed);
    s.exact_stop = rnd() < 0.05;
    p.push_back(s);
    at = e;
  }
  return p;
}

// Before the override was slewed and the look-ahead kept its walks whole,
// every one of these programs braked beyond the limit (jerk up to 20x).
TEST(MotionOverride, RandomProgramsUnderARandomOverrideKeepTheLimits) {
  for (std::uint32_t seed = 1; seed <= 12; ++seed) {
    for (const int every : {1, 5, 60}) {
      MotionInterpolator m;
      ASSERT_STREQ(m.configure({}, {0.0, 0.0}), "");
      std::uint32_t lcg = seed;
      const MotionRun run = run_program(m, random_program(seed), 600000, [&](std::size_t k, MotionInterpolator& mi) {
        if (k % static_cast<std::size_t>(every) != 0) return;
        lcg = lcg * 1664525u + 1013904223u;
        ASSERT_TRUE(mi.set_feed_override((lcg >> 28) == 0 ? 0.0 : 0.1 + 1.4 * static_cast<double>(lcg >> 8) / 16777216.0));
      });
      SCOPED_TRACE(testing::Message() << "seed " << seed << ", a new override every " << every << " ticks");
      EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-6);
      EXPECT_LE(run.jerk_ratio_max, 1.0 + 1e-6);
      EXPECT_EQ(m.stats().follower.brake_shortfalls, 0u);
      EXPECT_EQ(m.stats().follower.guard_failures, 0u);
      EXPECT_EQ(m.queued(), 0u) << "the program did not run to its end";
    }
  }
}

TEST(MotionOverride, ALowerOverrideAppliesAtTheNextTickAHigherOneSoonAfter) {
  MotionInterpolator m;
  ASSERT_STREQ(m.configure({}, {0.0, 0.0}), "");
  for (int i = 1; i <= 60; ++i) ASSERT_EQ(m.push(line_to({2.0 * i, 0.0}, 40.0)), SegmentRefusal::none);
  for (int k = 0; k < 400; ++k) m.tick();
  ASSERT_TRUE(m.set_feed_override(0.25));
  EXPECT_EQ(m.feed_override(), 0.25);
  EXPECT_EQ(m.effective_feed_override(), 1.0) << "nothing changes between two ticks";
  m.tick();
  EXPECT_EQ(m.effective_feed_override(), 0.25);
  ASSERT_TRUE(m.set_feed_override(1.5));
  // At the next tick, or once the look-ahead walk planned with the lower override is done.
  int waited = 0;
  while (m.effective_feed_override() < 1.5 && waited < 20) {
    m.tick();
    ++waited;
  }
  EXPECT_EQ(m.effective_feed_override(), 1.5);
  EXPECT_LE(waited, 10) << "ticks before the higher override came into force (a walk of 60 segments takes 8)";
  EXPECT_GE(waited, 2) << "a walk planned with 0.25 was still in progress";
}

}  // namespace
}  // namespace tnv::fw::motion
