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

TEST(Excitation, CarrierRunsThroughTheDrivePhaseOnly) {
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
  int carried = 0;
  while (g.active()) {
    if (g.carrier_mm_s() != 0.0) {
      EXPECT_EQ(g.carrier_mm_s(), 2.5);
      ++carried;
    }
    g.next(0);
  }
  EXPECT_EQ(carried, 200);
  EXPECT_EQ(g.carrier_mm_s(), 0.0);
  EXPECT_FALSE(g.has_carrier());
}

}  // namespace
}  // namespace tnv::fw
