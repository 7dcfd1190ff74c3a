// Real-time buffered shaping (issue item 3): the streaming output equals
// offline convolution of the same stream exactly, on an unbounded random
// command stream; final position and travel are unchanged; switching waits
// for a quiet buffer and makes no jump; enable is separate from the design.
#include "firmware/shaper/stream_shaper.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "firmware/shaper/shaper_design.hpp"
#include "tests/firmware/test_units.hpp"

namespace tnv::fw {
namespace {

using test_units::kPeriodS;

TapSet taps_for(ShaperType type, double f_hz, double zeta = 0.0, double f2_hz = 0.0) {
  return design_shaper({type, {f_hz, zeta}, {f2_hz, zeta}}, kPeriodS).taps;
}

// An operator-like stream: random jog speeds held for random times, with
// stops, integrated to position; some samples exactly at rest.
std::vector<AxisSample> random_stream(std::size_t n, unsigned seed, double start_mm) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> speed(-80.0, 80.0);
  std::uniform_int_distribution<int> hold(1, 400);
  std::bernoulli_distribution stop(0.3);
  std::vector<AxisSample> out;
  out.reserve(n);
  double x = start_mm, v = 0.0;
  while (out.size() < n) {
    const double target = stop(rng) ? 0.0 : speed(rng);
    for (int k = hold(rng); k > 0 && out.size() < n; --k) {
      const double v1 = v + std::clamp(target - v, -2.0, 2.0);
      x += 0.5 * (v + v1) * kPeriodS;
      v = v1;
      out.push_back({x, v});
    }
  }
  return out;
}

void configure(StreamShaper& s, const TapSet& taps, const AxisSample& rest) {
  ASSERT_TRUE(s.request_taps(taps));
  s.request_enabled(true);
  s.reset(rest);
  ASSERT_TRUE(s.shaping());
}

TEST(StreamShaper, EqualsOfflineConvolutionOnAnUnboundedRandomStream) {
  // 200 s of stream: the 1024-sample ring wraps ~200 times.
  const std::size_t n = 200'000;
  const AxisSample rest{123.456, 0.0};
  const std::vector<AxisSample> in = random_stream(n, 7, rest.position_mm);
  for (const TapSet& taps : {taps_for(ShaperType::zvd, 31.7, 0.02), taps_for(ShaperType::zvdd, 5.0, 0.3, 5.0),
                             taps_for(ShaperType::ei, 87.0, 0.05, 143.5)}) {
    StreamShaper s;
    configure(s, taps, rest);
    std::vector<AxisSample> offline(n);
    shape_offline(taps, in.data(), offline.data(), n, rest);
    std::size_t mismatches = 0;
    long double worst_direct_mm = 0.0L;
    for (std::size_t k = 0; k < n; ++k) {
      const AxisSample y = s.step(in[k]);
      if (y.position_mm != offline[k].position_mm || y.speed_mm_s != offline[k].speed_mm_s) ++mismatches;
      if (k % 97 == 0) {  // the textbook sum, in long double
        long double direct = 0.0L;
        for (std::size_t j = 0; j < taps.count; ++j) {
          const std::size_t d = taps.tap[j].k;
          direct += static_cast<long double>(taps.tap[j].a) * (d <= k ? in[k - d].position_mm : rest.position_mm);
        }
        worst_direct_mm = std::fmax(worst_direct_mm, std::fabs(direct - static_cast<long double>(y.position_mm)));
      }
    }
    EXPECT_EQ(mismatches, 0u) << "samples where streaming and offline shaping differ (span " << taps.span() << ")";
    EXPECT_LT(static_cast<double>(worst_direct_mm), 1e-11) << "mm, against sum_j a_j x_{k-k_j}";
  }
}

TEST(StreamShaper, FinalPositionAndTravelAreUnchanged) {
  const AxisSample rest{-17.3, 0.0};
  std::vector<AxisSample> in = random_stream(30'000, 11, rest.position_mm);
  const AxisSample end{in.back().position_mm, 0.0};
  in.insert(in.end(), 2'000, end);  // the stream stops and stays
  for (ShaperType type : kShaperTypes) {
    StreamShaper s;
    configure(s, taps_for(type, 13.0, 0.05, 41.0), rest);
    AxisSample y{};
    for (const AxisSample& x : in) y = s.step(x);
    EXPECT_EQ(y.position_mm, end.position_mm) << to_string(type) << ": final position";
    EXPECT_EQ(y.speed_mm_s, 0.0) << to_string(type);
    EXPECT_EQ(y.position_mm - rest.position_mm, end.position_mm - rest.position_mm) << to_string(type) << ": travel";
    EXPECT_TRUE(s.quiet());
  }
}

TEST(StreamShaper, ARampComesOutDelayedByTheCentroid) {
  const TapSet taps = taps_for(ShaperType::zvd, 30.0, 0.02);
  StreamShaper s;
  configure(s, taps, {0.0, 0.0});
  const double v_mm_s = 20.0;
  AxisSample y{};
  for (int k = 1; k <= 500; ++k) y = s.step({v_mm_s * k * kPeriodS, v_mm_s});
  EXPECT_NEAR(0.5 - y.position_mm / v_mm_s, taps.centroid_samples() * kPeriodS, 1e-12) << "delay (s)";
  EXPECT_NEAR(y.speed_mm_s, v_mm_s, 1e-12);
  EXPECT_NEAR(s.delay_samples(), taps.centroid_samples(), 0.0);
}

TEST(StreamShaper, DisabledIsTheIdentityBitForBitEvenWithTapsSet) {
  StreamShaper s;
  ASSERT_TRUE(s.request_taps(taps_for(ShaperType::zvdd, 20.0)));
  s.reset({1.0, 0.0});
  EXPECT_FALSE(s.shaping()) << "a design alone does not enable the shaper";
  for (const AxisSample& x : random_stream(5'000, 3, 1.0)) {
    const AxisSample y = s.step(x);
    ASSERT_EQ(y.position_mm, x.position_mm);
    ASSERT_EQ(y.speed_mm_s, x.speed_mm_s);
  }
  EXPECT_EQ(s.delay_samples(), 0.0);
}

// Switching mid-stream: waits for a quiet buffer, then the new shaper
// starts from rest; the output never jumps, and afterwards it is exactly
// the offline shaping of the rest of the stream.
TEST(StreamShaper, SwitchesOnlyWhenQuietAndWithoutAJump) {
  const TapSet zv30 = taps_for(ShaperType::zv, 30.0);
  const TapSet zvd60 = taps_for(ShaperType::zvd, 60.0);
  StreamShaper s;
  configure(s, zv30, {0.0, 0.0});
  // A move, then rest at 5 mm, then a second move.
  std::vector<AxisSample> in;
  double x = 0.0;
  const auto move = [&](double v, int ticks) {
    for (int k = 0; k < ticks; ++k) {
      x += v * kPeriodS;
      in.push_back({x, v});
    }
  };
  move(50.0, 100);
  const std::size_t rest_from = in.size();
  for (int k = 0; k < 100; ++k) in.push_back({x, 0.0});
  const std::size_t second_from = in.size();
  move(-30.0, 100);
  for (int k = 0; k < 100; ++k) in.push_back({x, 0.0});

  std::vector<AxisSample> out;
  std::size_t applied_at = 0;
  for (std::size_t k = 0; k < in.size(); ++k) {
    if (k == 20) {
      ASSERT_TRUE(s.request_taps(zvd60));  // asked for mid-move
      EXPECT_TRUE(s.change_pending());
    }
    out.push_back(s.step(in[k]));
    if (k > 20 && applied_at == 0 && !s.change_pending()) applied_at = k;
    if (s.change_pending()) {
      EXPECT_EQ(s.active_taps().span(), zv30.span()) << "switched while not quiet, tick " << k;
    }
  }
  ASSERT_GT(applied_at, rest_from + zv30.span()) << "the switch must wait for the old shaper to finish";
  ASSERT_LT(applied_at, second_from);
  double worst_jump_mm = 0.0;
  for (std::size_t k = 1; k < out.size(); ++k)
    worst_jump_mm = std::fmax(worst_jump_mm, std::fabs(out[k].position_mm - out[k - 1].position_mm));
  EXPECT_LE(worst_jump_mm, 50.0 * kPeriodS + 1e-12) << "mm per tick: no faster than the input ever moves";
  std::vector<AxisSample> offline(in.size() - applied_at);
  shape_offline(zvd60, in.data() + applied_at, offline.data(), offline.size(), in[applied_at - 1]);
  for (std::size_t k = applied_at; k < in.size(); ++k)
    ASSERT_EQ(out[k].position_mm, offline[k - applied_at].position_mm) << "tick " << k;
  EXPECT_EQ(out.back().position_mm, in.back().position_mm);
}

TEST(StreamShaper, EnableAndDisableAlsoWaitForQuiet) {
  StreamShaper s;
  ASSERT_TRUE(s.request_taps(taps_for(ShaperType::zv, 25.0)));
  s.reset({0.0, 0.0});
  s.step({0.01, 10.0});
  s.request_enabled(true);
  s.step({0.02, 10.0});
  EXPECT_FALSE(s.shaping()) << "enabled while the stream was moving";
  s.step({0.02, 0.0});
  s.step({0.02, 0.0});
  EXPECT_TRUE(s.shaping());
  s.step({0.03, 10.0});
  s.request_enabled(false);
  for (int k = 0; k < 10; ++k) s.step({0.03, 0.0});
  EXPECT_TRUE(s.shaping()) << "disabled before the 20 ms shaper had finished";
  for (int k = 0; k < 20; ++k) s.step({0.03, 0.0});
  EXPECT_FALSE(s.shaping());
  EXPECT_EQ(s.output().position_mm, 0.03);
}

TEST(StreamShaper, ResetAppliesAPendingChangeAtOnce) {
  StreamShaper s;
  ASSERT_TRUE(s.request_taps(taps_for(ShaperType::mzv, 40.0)));
  s.request_enabled(true);
  EXPECT_TRUE(s.change_pending());
  s.reset({2.0, 0.0});
  EXPECT_FALSE(s.change_pending());
  EXPECT_TRUE(s.shaping());
  EXPECT_EQ(s.output().position_mm, 2.0);
}

TEST(StreamShaper, RefusesTapsItCannotRunAndKeepsTheOldOnes) {
  StreamShaper s;
  const TapSet good = taps_for(ShaperType::zv, 30.0);
  ASSERT_TRUE(s.request_taps(good));
  TapSet too_long;
  too_long.add(0, 0.5);
  too_long.add(StreamShaper::kRingCapacity, 0.5);
  EXPECT_FALSE(s.request_taps(too_long));
  TapSet not_unit;
  not_unit.add(0, 0.5);
  not_unit.add(3, 0.4);
  EXPECT_FALSE(s.request_taps(not_unit));
  TapSet nan_tap = good;
  nan_tap.tap[1].a = std::nan("");
  EXPECT_FALSE(s.request_taps(nan_tap));
  EXPECT_FALSE(s.request_taps(TapSet{}));
  s.request_enabled(true);
  s.reset({0.0, 0.0});
  EXPECT_EQ(s.active_taps().span(), good.span());
}

}  // namespace
}  // namespace tnv::fw
