// The reference-plant axis: exact ZOH discretisation, Karnopp stick/slip,
// exact zero-crossing location.
#include "emulator/axis_plant.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tnv::emu {
namespace {

constexpr double kT_s = 1e-3;  // control period: 100 sub-steps

AxisPlantParams frictionless(double tau_s) {
  return AxisPlantParams{.tau_s = tau_s, .gain = 1.0, .coulomb_mm_s = 0.0, .stiction_mm_s = 0.0};
}

struct Zoh {
  double a12, a22, b1, b2;
};

// Identify A, B of one 1 ms period by stepping from unit initial states.
Zoh identify(const AxisPlantParams& params) {
  AxisPlant plant(params);
  Zoh zoh{};
  plant.set_state(0.0, 1.0);
  for (int i = 0; i < 100; ++i) plant.step(0.0, 0.0);
  zoh.a12 = plant.position_mm();
  zoh.a22 = plant.speed_mm_s();
  plant.set_state(0.0, 0.0);
  for (int i = 0; i < 100; ++i) plant.step(1.0, 0.0);
  zoh.b1 = plant.position_mm();
  zoh.b2 = plant.speed_mm_s();
  return zoh;
}

class ZohPerAxis : public ::testing::TestWithParam<double> {};

TEST_P(ZohPerAxis, HundredSubstepsEqualExactOneMillisecondZoh) {
  const double tau_s = GetParam();
  const Zoh zoh = identify(frictionless(tau_s));
  const double a22 = std::exp(-kT_s / tau_s);
  const double a12 = tau_s * (1.0 - a22);
  EXPECT_NEAR(zoh.a12, a12, 1e-12) << "A12 (mm per mm/s) for tau = " << tau_s << " s";
  EXPECT_NEAR(zoh.a22, a22, 1e-12) << "A22 for tau = " << tau_s << " s";
  EXPECT_NEAR(zoh.b1, kT_s - a12, 1e-12) << "B1 (mm per mm/s of command)";
  EXPECT_NEAR(zoh.b2, 1.0 - a22, 1e-12) << "B2";
}

INSTANTIATE_TEST_SUITE_P(XAndY, ZohPerAxis, ::testing::Values(0.005360, 0.007122));

TEST(AxisPlantZoh, GainScalesInputColumn) {
  AxisPlantParams params = frictionless(0.005360);
  params.gain = 1.25;
  const Zoh zoh = identify(params);
  const double a22 = std::exp(-kT_s / params.tau_s);
  EXPECT_NEAR(zoh.b1, 1.25 * (kT_s - params.tau_s * (1.0 - a22)), 1e-12);
  EXPECT_NEAR(zoh.b2, 1.25 * (1.0 - a22), 1e-12);
}

TEST(AxisPlantZoh, MatchesReferencePlantPrintedDigits) {
  const Zoh x = identify(frictionless(0.005360));
  const Zoh y = identify(frictionless(0.007122));
  EXPECT_NEAR(x.a12, 0.0009123, 0.5e-7);
  EXPECT_NEAR(y.a12, 0.0009330, 0.5e-7);
  EXPECT_NEAR(x.b1, 0.0000877, 0.5e-7);
  EXPECT_NEAR(y.b1, 0.0000670, 0.5e-7);
  EXPECT_NEAR(x.a22, 0.8298, 0.5e-4);
  EXPECT_NEAR(y.a22, 0.8690, 0.5e-4);
  // S1 eq. (31), four decimals
  EXPECT_NEAR(x.a12, 0.0009, 0.5e-4);
  EXPECT_NEAR(x.b1, 0.0001, 0.5e-4);
  EXPECT_NEAR(x.b2, 0.1702, 0.5e-4);
  EXPECT_NEAR(y.b2, 0.1310, 0.5e-4);
}

TEST(AxisPlantFriction, OffMeansNeverStuck) {
  AxisPlant plant(frictionless(0.005360));
  EXPECT_FALSE(plant.friction_enabled());
  plant.set_state(0.0, 0.0, true);
  EXPECT_FALSE(plant.stuck());
  plant.step(0.001, 0.0);
  EXPECT_GT(plant.speed_mm_s(), 0.0) << "a frictionless axis must move under any command";
}

TEST(AxisPlantFriction, StuckAxisStaysStuckAtOrBelowStiction) {
  AxisPlant plant(AxisPlantParams{});
  plant.set_state(1.0, 0.0, true);
  for (int i = 0; i < 10'000; ++i) plant.step(2.0, 0.99);  // |K u + d| = 2.99 <= f_s = 3
  EXPECT_TRUE(plant.stuck());
  EXPECT_EQ(plant.speed_mm_s(), 0.0);
  EXPECT_EQ(plant.position_mm(), 1.0) << "a stuck axis moved";
  plant.step(-3.0, 0.0);  // exactly f_s: still held
  EXPECT_TRUE(plant.stuck());
}

TEST(AxisPlantFriction, BreaksAwayAboveStictionWithFrictionAtStictionLevel) {
  const AxisPlantParams params{};
  AxisPlant plant(params);
  plant.set_state(0.0, 0.0, true);
  plant.step(3.1, 0.0);
  EXPECT_FALSE(plant.stuck());
  // First sub-step: friction held at f_s, w = 3.1 - 3.0.
  const double e = std::exp(-1e-5 / params.tau_s);
  EXPECT_NEAR(plant.speed_mm_s(), 0.1 * (1.0 - e), 1e-15) << "break-away speed after one sub-step";
  EXPECT_NEAR(plant.position_mm(), 0.1 * 1e-5 - 0.1 * params.tau_s * (1.0 - e), 1e-18);
  // Negative side, driven by the disturbance alone.
  plant.set_state(0.0, 0.0, true);
  plant.step(0.0, -3.5);
  EXPECT_LT(plant.speed_mm_s(), 0.0);
  EXPECT_NEAR(plant.speed_mm_s(), -0.5 * (1.0 - e), 1e-15);
}

TEST(AxisPlantFriction, RestingButNotFlaggedStuckGetsTheKarnoppTest) {
  AxisPlant plant(AxisPlantParams{});
  plant.set_state(0.0, 0.0, false);
  plant.step(1.0, 0.0);
  EXPECT_TRUE(plant.stuck());
  EXPECT_EQ(plant.speed_mm_s(), 0.0);
  EXPECT_EQ(plant.position_mm(), 0.0);
}

TEST(AxisPlantFriction, ZeroCrossingIsLocatedExactly) {
  const AxisPlantParams params{};
  const double tau_s = params.tau_s;
  // v0 = 1 mm/s is > 6.5 v_s, so the held friction is exactly f_c = 1.5.
  const double v0 = 1.0;
  const double w = 0.0 - 1.5;
  const double crossing_s = tau_s * std::log((w - v0) / w);  // 0 = w + (v0 - w) e^{-t/tau}
  const double crossing_position_mm = w * crossing_s + (v0 - w) * tau_s * (1.0 - std::exp(-crossing_s / tau_s));

  AxisPlant before(params);
  before.set_state(0.0, v0);
  before.step_for(0.0, 0.0, (1.0 - 1e-9) * crossing_s);
  EXPECT_GT(before.speed_mm_s(), 0.0) << "stopped before the analytic crossing time " << crossing_s * 1e3 << " ms";
  EXPECT_FALSE(before.stuck());

  AxisPlant after(params);
  after.set_state(0.0, v0);
  after.step_for(0.0, 0.0, (1.0 + 1e-9) * crossing_s);
  EXPECT_TRUE(after.stuck());
  EXPECT_EQ(after.speed_mm_s(), 0.0);
  EXPECT_NEAR(after.position_mm(), crossing_position_mm, 1e-15) << "position at the crossing, mm";
}

TEST(AxisPlantFriction, CrossingExactlyAtTheEndOfTheStepSticks) {
  const AxisPlantParams params{};
  const double v0 = 2.0;
  const double w = -1.5;
  const double crossing_s = params.tau_s * std::log((w - v0) / w);
  AxisPlant plant(params);
  plant.set_state(0.0, v0);
  plant.step_for(0.0, 0.0, crossing_s);
  EXPECT_TRUE(plant.stuck()) << "speed left at " << plant.speed_mm_s() << " mm/s";
  EXPECT_EQ(plant.speed_mm_s(), 0.0);
}

TEST(AxisPlantFriction, CrossingInsideOneSubstepStopsAtTheAnalyticPosition) {
  const AxisPlantParams params{};
  StribeckFriction friction(params.coulomb_mm_s, params.stiction_mm_s, params.stribeck_mm_s);
  const double v0 = -0.002;
  const double w = 0.0 - friction.slipping_mm_s(v0);  // ~ +3 mm/s against the motion
  const double crossing_s = params.tau_s * std::log((w - v0) / w);
  ASSERT_LT(crossing_s, 1e-5);
  AxisPlant plant(params);
  plant.set_state(5.0, v0);
  plant.step(0.0, 0.0);
  EXPECT_TRUE(plant.stuck());
  EXPECT_EQ(plant.speed_mm_s(), 0.0);
  const double expected_mm = 5.0 + w * crossing_s + (v0 - w) * params.tau_s * (1.0 - std::exp(-crossing_s / params.tau_s));
  EXPECT_NEAR(plant.position_mm(), expected_mm, 4e-15);
  plant.step(0.0, 0.0);
  EXPECT_TRUE(plant.stuck()) << "no drive: must stay stuck";
}

TEST(AxisPlantFriction, DeceleratingAxisComesToRestAndStays) {
  AxisPlant plant(AxisPlantParams{});
  plant.set_state(0.0, 5.0);
  for (int i = 0; i < 5'000; ++i) plant.step(1.0, 0.0);  // 50 ms, command below f_c
  ASSERT_TRUE(plant.stuck()) << "still moving at " << plant.speed_mm_s() << " mm/s after 50 ms";
  const double rest_mm = plant.position_mm();
  EXPECT_GT(rest_mm, 0.0);
  for (int i = 0; i < 5'000; ++i) {
    plant.step(1.0, 0.0);
    ASSERT_EQ(plant.speed_mm_s(), 0.0) << "restarted at sub-step " << i;
  }
  EXPECT_EQ(plant.position_mm(), rest_mm);
}

TEST(AxisPlantFriction, SlidingAboveCoulombReachesSteadySpeed) {
  AxisPlant plant(AxisPlantParams{});
  plant.set_state(0.0, 0.0, true);
  for (int i = 0; i < 20'000; ++i) plant.step(5.0, 0.0);  // 200 ms >> tau
  EXPECT_NEAR(plant.speed_mm_s(), 5.0 - 1.5, 1e-9) << "steady speed = K u - f_c when v >> v_s";
}

// advance_held_block is a shortcut, never a different model.
struct BlockCase {
  const char* what;
  AxisPlantParams params;
  double v0_mm_s, command_mm_s, disturbance_mm_s;
  bool stuck;
  bool closed_form_expected;
};

AxisPlantParams accel_limited(double accel_limit_mm_s2) {
  AxisPlantParams p;
  p.accel_limit_mm_s2 = accel_limit_mm_s2;
  return p;
}

class AxisPlantBlock : public ::testing::TestWithParam<BlockCase> {};

TEST_P(AxisPlantBlock, ClosedFormEqualsSteppingOrDeclines) {
  const BlockCase& c = GetParam();
  const AxisPlant plant(c.params);
  AxisState stepped{1.0, c.v0_mm_s, c.stuck};
  for (int i = 0; i < 100; ++i) plant.advance(stepped, c.command_mm_s, c.disturbance_mm_s);
  AxisState block{1.0, c.v0_mm_s, c.stuck};
  const bool done = plant.advance_held_block(block, c.command_mm_s, c.disturbance_mm_s, 100);
  ASSERT_EQ(done, c.closed_form_expected) << c.what;
  if (!done) {
    EXPECT_EQ(block.position_mm, 1.0) << c.what << ": a declined block changed the state";
    EXPECT_EQ(block.speed_mm_s, c.v0_mm_s);
    EXPECT_EQ(block.stuck, c.stuck);
    return;
  }
  EXPECT_NEAR(block.position_mm, stepped.position_mm, 1e-14) << c.what << ": position, mm";
  EXPECT_NEAR(block.speed_mm_s, stepped.speed_mm_s, 1e-13) << c.what << ": speed, mm/s";
  EXPECT_EQ(block.stuck, stepped.stuck) << c.what;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, AxisPlantBlock,
    ::testing::Values(
        BlockCase{"cruising forward", AxisPlantParams{}, 2.0, 3.6, 0.5, false, true},
        BlockCase{"cruising backward", AxisPlantParams{}, -2.0, -3.4, -0.3, false, true},
        BlockCase{"decelerating, stays clear of the Stribeck zone", AxisPlantParams{}, 3.0, 2.5, 0.0, false, true},
        BlockCase{"heading for the Stribeck zone, still clear of it after 1 ms", AxisPlantParams{}, 2.0, 1.8, 0.0,
                  false, true},
        BlockCase{"heading for zero, clear of the zone after 1 ms", AxisPlantParams{}, 2.0, -3.0, 0.0, false, true},
        BlockCase{"friction off, through zero", frictionless(0.007122), 1.0, -1.0, 0.2, false, true},
        BlockCase{"stuck, drive within stiction", AxisPlantParams{}, 0.0, 2.9, -0.4, true, true},
        BlockCase{"at rest, drive within stiction: sticks", AxisPlantParams{}, 0.0, -3.0, 0.0, false, true},
        BlockCase{"under the acceleration limit, small step", accel_limited(1000.0), 2.0, 4.0, 0.0, false, true},
        BlockCase{"reaching the Stribeck zone within 1 ms", AxisPlantParams{}, 0.8, 0.5, 0.0, false, false},
        BlockCase{"through zero within 1 ms", AxisPlantParams{}, 0.9, -8.0, 0.0, false, false},
        BlockCase{"starting inside the Stribeck zone", AxisPlantParams{}, 0.3, 3.0, 0.0, false, false},
        BlockCase{"at rest, breaking away", AxisPlantParams{}, 0.0, 5.0, 0.0, true, false},
        BlockCase{"on the acceleration limit's ramp", accel_limited(1000.0), 2.0, 20.0, 0.0, false, false}),
    [](const ::testing::TestParamInfo<BlockCase>& param_info) { return std::to_string(param_info.index); });

// advance_held, the closed form where it holds and sub-steps elsewhere,
// follows the sub-steps through every switch: into and out of the Stribeck
// zone, through zero, sticking, breaking away.
struct HeldCase {
  const char* what;
  AxisPlantParams params;
  double v0_mm_s, command_mm_s;
  bool stuck;
};

class AxisPlantHeld : public ::testing::TestWithParam<HeldCase> {};

TEST_P(AxisPlantHeld, EqualsSteppingForAnyBlockLength) {
  const HeldCase& c = GetParam();
  const AxisPlant plant(c.params);
  for (const std::size_t count : {std::size_t{1}, std::size_t{7}, std::size_t{50}, std::size_t{100}}) {
    AxisState stepped{1.0, c.v0_mm_s, c.stuck};
    AxisState held = stepped;
    // Ten blocks in a row, so each starts where the last one left the axis.
    for (int block = 0; block < 10; ++block) {
      for (std::size_t i = 0; i < count; ++i) plant.advance(stepped, c.command_mm_s, 0.25);
      plant.advance_held(held, c.command_mm_s, 0.25, count);
      ASSERT_NEAR(held.position_mm, stepped.position_mm, 1e-13) << c.what << ", blocks of " << count;
      ASSERT_NEAR(held.speed_mm_s, stepped.speed_mm_s, 1e-12) << c.what << ", blocks of " << count;
      ASSERT_EQ(held.stuck, stepped.stuck) << c.what << ", blocks of " << count;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, AxisPlantHeld,
    ::testing::Values(HeldCase{"cruising", AxisPlantParams{}, 2.0, 3.6, false},
                      HeldCase{"decelerating into the zone and sticking", AxisPlantParams{}, 1.5, 1.0, false},
                      HeldCase{"reversing through zero", AxisPlantParams{}, 1.5, -6.0, false},
                      HeldCase{"breaking away and leaving the zone", AxisPlantParams{}, 0.0, 6.0, true},
                      HeldCase{"stuck, held by stiction", AxisPlantParams{}, 0.0, -3.2, true},
                      HeldCase{"creeping inside the zone", AxisPlantParams{}, 0.05, 1.6, false},
                      HeldCase{"acceleration limit, reversing", accel_limited(1000.0), 2.0, -20.0, false},
                      HeldCase{"friction off", frictionless(0.005360), -1.0, 2.0, false}),
    [](const ::testing::TestParamInfo<HeldCase>& param_info) { return std::to_string(param_info.index); });

}  // namespace
}  // namespace tnv::emu
