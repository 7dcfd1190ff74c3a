// Open-loop excitation generator (issue 7, item 1): step and ramp shapes,
// the breakaway stop, validation.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "firmware/compensation/excitation.hpp"

namespace tnv::fw {
namespace {

TEST(Excitation, StepHoldsTheLevelThenSettlesAtZero) {
  ExcitationSpec spec;
  spec.kind = ExcitationKind::step;
  spec.level_mm_s = -7.5;
  spec.duration_s = 0.010;
  spec.settle_s = 0.005;
  ExcitationGenerator gen;
  gen.start(spec);
  for (int k = 0; k < 10; ++k) EXPECT_EQ(gen.next(0), -7.5) << "tick " << k;
  int zeros = 0;
  while (gen.active()) {
    EXPECT_EQ(gen.next(0), 0.0);
    ++zeros;
    ASSERT_LT(zeros, 100);
  }
  EXPECT_EQ(zeros, 6);  // the stop tick and 5 settle ticks
}

TEST(Excitation, RampRisesAtItsRateAndStopsAtBreakaway) {
  ExcitationSpec spec;
  spec.kind = ExcitationKind::ramp;
  spec.level_mm_s = 5.0;
  spec.rate_mm_s2 = 2.0;
  spec.duration_s = 5.0;
  spec.settle_s = 0.0;
  spec.breakaway_counts = 3;
  ExcitationGenerator gen;
  gen.start(spec);
  EXPECT_NEAR(gen.next(0), 0.0, 1e-12);
  EXPECT_NEAR(gen.next(0), 0.002, 1e-12);  // mm/s after 1 ms at 2 mm/s^2
  for (int k = 2; k < 1000; ++k) gen.next(0);
  EXPECT_NEAR(gen.next(1), 2.0, 1e-9);  // moved one count: still ramping
  EXPECT_EQ(gen.breakaway_tick(), 1000);
  EXPECT_EQ(gen.next(3), 0.0);  // three counts: the ramp ends
  EXPECT_FALSE(gen.active());
}

TEST(Excitation, RampIsLimitedByItsLevel) {
  ExcitationSpec spec;
  spec.kind = ExcitationKind::ramp;
  spec.level_mm_s = -1.0;
  spec.rate_mm_s2 = 100.0;
  spec.duration_s = 1.0;
  ExcitationGenerator gen;
  gen.start(spec);
  double u = 0.0;
  for (int k = 0; k < 100; ++k) u = gen.next(0);
  EXPECT_NEAR(u, -1.0, 1e-12);
}

TEST(Excitation, ValidationNamesTheField) {
  ExcitationSpec spec;
  EXPECT_TRUE(validate(spec).ok);
  spec.level_mm_s = std::numeric_limits<double>::quiet_NaN();
  EXPECT_STREQ(validate(spec).field, "level_mm_s");
  spec = {};
  spec.level_mm_s = 0.0;
  EXPECT_STREQ(validate(spec).field, "level_mm_s");
  spec = {};
  spec.duration_s = 0.0;
  EXPECT_STREQ(validate(spec).field, "duration_s");
  spec = {};
  spec.kind = ExcitationKind::ramp;
  spec.rate_mm_s2 = -1.0;
  EXPECT_STREQ(validate(spec).field, "rate_mm_s2");
  spec = {};
  spec.kind = ExcitationKind::ramp;
  spec.breakaway_counts = 0;
  EXPECT_STREQ(validate(spec).field, "breakaway_counts");
}

TEST(Excitation, CarrierIsCheckedAndOnlyForTheClosedLoopKinds) {
  ExcitationSpec spec;
  spec.kind = ExcitationKind::multisine;
  spec.duration_s = 4.0;
  spec.carrier_mm_s = 3.0;
  EXPECT_TRUE(validate(spec).ok);
  spec.carrier_mm_s = -kExcitationMaxCarrierMmS;
  EXPECT_TRUE(validate(spec).ok);
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 20.5}) {
    spec.carrier_mm_s = bad;
    EXPECT_STREQ(validate(spec).field, "carrier_mm_s") << bad;
  }
  for (const ExcitationKind open : {ExcitationKind::step, ExcitationKind::ramp, ExcitationKind::multisine_open}) {
    ExcitationSpec o;
    o.kind = open;
    o.duration_s = 4.0;
    o.carrier_mm_s = 1.0;
    EXPECT_STREQ(validate(o).field, "carrier_mm_s") << static_cast<int>(open);
  }
}

// The carrier ramps in and out, never stepping by more than 1/R of itself
// per tick, holds its speed in between, and travels exactly carrier x drive
// phase (what the host moves the table back by).
TEST(Excitation, CarrierRampsInAndOutAndTravelsCarrierTimesTheDrivePhase) {
  ExcitationSpec spec;
  spec.kind = ExcitationKind::multisine;
  spec.f_min_hz = 10.0;
  spec.f_max_hz = 100.0;
  spec.tones = 5;
  spec.duration_s = 0.25;  // 2 whole periods of 100 ticks
  spec.carrier_mm_s = 2.5;
  ExcitationGenerator g;
  g.start(spec);
  ASSERT_EQ(g.drive_ticks(), 200);
  const double max_step = 2.5 / static_cast<double>(kCarrierRampTicks) + 1e-12;
  double previous = 0.0, travel_ticks_x_speed = 0.0;
  std::int64_t k = 0;
  while (g.active()) {
    const double v = g.carrier_mm_s();
    EXPECT_LE(std::fabs(v - previous), max_step) << "tick " << k;
    EXPECT_GE(v, 0.0) << "tick " << k;
    EXPECT_LE(v, 2.5) << "tick " << k;
    if (k >= kCarrierRampTicks - 1 && k < g.drive_ticks()) {
      EXPECT_EQ(v, 2.5) << "tick " << k;
    }
    if (k >= g.drive_ticks() + kCarrierRampTicks - 1) {
      EXPECT_EQ(v, 0.0) << "tick " << k;
    }
    travel_ticks_x_speed += v;
    previous = v;
    g.next(0);
    ++k;
  }
  EXPECT_GE(k, g.drive_ticks() + kCarrierRampTicks);  // the settle covers the ramp out
  EXPECT_NEAR(travel_ticks_x_speed, 2.5 * 200.0, 1e-9);
  EXPECT_EQ(g.carrier_mm_s(), 0.0);
  EXPECT_FALSE(g.has_carrier());
}

TEST(Excitation, ACarrierNeedsASettleThatCoversItsRampOut) {
  ExcitationSpec spec;
  spec.kind = ExcitationKind::sweep;
  spec.f_min_hz = 10.0;
  spec.f_max_hz = 100.0;
  spec.duration_s = 1.0;
  spec.carrier_mm_s = 3.0;
  spec.settle_s = 0.01;
  EXPECT_STREQ(validate(spec).field, "settle_s");
  spec.settle_s = 0.05;
  EXPECT_TRUE(validate(spec).ok);
  spec.carrier_mm_s = 0.0;
  spec.settle_s = 0.0;
  EXPECT_TRUE(validate(spec).ok);  // a standing table needs no ramp
}

}  // namespace
}  // namespace tnv::fw
