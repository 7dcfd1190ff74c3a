// The vertical axis (reference plant "Z axis"): the axis law with gravity in
// the Karnopp stick rule, its end stops and home switch.
#include "emulator/z_axis_plant.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tnv::emu {
namespace {

constexpr double kT_s = 1e-3;         // control period: 100 sub-steps
constexpr int kSubstepsPerTick = 100;
constexpr double kTauZ_s = 0.009;     // reference plant

ZAxisPlant frictionless(double gravity_mm_s) {
  ZAxisParams z;
  AxisPlantParams law = kZAxisLaw;
  law.coulomb_mm_s = 0.0;
  law.stiction_mm_s = 0.0;
  z.gravity_mm_s = gravity_mm_s;
  return ZAxisPlant(z, law);
}

void run(ZAxisPlant& z, double command_mm_s, int substeps, double push_mm_s = 0.0) {
  for (int i = 0; i < substeps; ++i) z.step(command_mm_s, push_mm_s);
}

TEST(ZAxisPlant, DefaultsAreTheReferencePlant) {
  const ZAxisParams z{};
  // Z's law is the scenario's [plant.z], like every axis'.
  const AxisPlantParams law = Scenario{}.plant[hal::index(hal::Axis::z)];
  EXPECT_EQ(law.tau_s, kTauZ_s);
  EXPECT_EQ(law.gain, 1.0);
  EXPECT_EQ(law.coulomb_mm_s, 2.0);
  EXPECT_EQ(law.stiction_mm_s, 4.0);
  EXPECT_EQ(law.stribeck_mm_s, 0.1);
  EXPECT_EQ(law.mode_hz, 0.0);
  EXPECT_EQ(law.backlash_um, 0.0);
  EXPECT_EQ(z.gravity_mm_s, -1.0);
  EXPECT_EQ(z.travel_top_mm, 0.0);
  EXPECT_EQ(z.travel_bottom_mm, -300.0);
}

TEST(ZAxisPlant, HundredSubstepsEqualTheExactOneMillisecondZoh) {
  // Friction and gravity off: the plant is the exact ZOH of tau_Z.
  ZAxisPlant z = frictionless(0.0);
  const double a22 = std::exp(-kT_s / kTauZ_s);
  const double a12 = kTauZ_s * (1.0 - a22);
  z.set_state(-100.0, 1.0);
  run(z, 0.0, kSubstepsPerTick);
  EXPECT_NEAR(z.position_mm() + 100.0, a12, 1e-12) << "A12";
  EXPECT_NEAR(z.speed_mm_s(), a22, 1e-12) << "A22";
  z.set_state(-100.0, 0.0);
  run(z, 1.0, kSubstepsPerTick);
  EXPECT_NEAR(z.position_mm() + 100.0, kT_s - a12, 1e-12) << "B1";
  EXPECT_NEAR(z.speed_mm_s(), 1.0 - a22, 1e-12) << "B2";
}

TEST(ZAxisPlant, GravityIsAConstantInputThroughTheSameZoh) {
  ZAxisPlant z = frictionless(-1.0);
  const double a22 = std::exp(-kT_s / kTauZ_s);
  z.set_state(-100.0, 0.0);
  run(z, 0.0, kSubstepsPerTick);
  EXPECT_NEAR(z.speed_mm_s(), -(1.0 - a22), 1e-12) << "an unheld frictionless head falls as B d_g";
  EXPECT_NEAR(z.position_mm() + 100.0, -(kT_s - kTauZ_s * (1.0 - a22)), 1e-12);
}

TEST(ZAxisPlant, CommandingPlusOneHoldsAgainstGravity) {
  ZAxisPlant frictionless_z = frictionless(-1.0);
  frictionless_z.set_state(-100.0, 0.0);
  run(frictionless_z, 1.0, 100'000);  // 1 s
  EXPECT_EQ(frictionless_z.speed_mm_s(), 0.0);
  EXPECT_EQ(frictionless_z.position_mm(), -100.0) << "u = +1.0 mm/s balances d_g exactly";
  ZAxisPlant held = frictionless(-1.0);
  held.set_state(-100.0, 0.0);
  run(held, 0.9, 100'000);
  EXPECT_LT(held.position_mm(), -100.05) << "0.9 mm/s does not hold a frictionless head (it sinks at 0.1 mm/s)";
  ZAxisPlant z(ZAxisParams{});
  z.set_state(-100.0, 0.0, true);
  run(z, 1.0, 100'000);
  EXPECT_EQ(z.position_mm(), -100.0);
}

TEST(ZAxisPlant, IdleStuckHeadDoesNotSag) {
  ZAxisPlant z(ZAxisParams{});
  z.set_state(-120.0, 0.0, true);
  run(z, 0.0, 200'000);  // 2 s of u = 0: |u + d_g| = 1 <= f_s = 4
  EXPECT_TRUE(z.stuck());
  EXPECT_EQ(z.position_mm(), -120.0);
  // Not flagged stuck but at rest: the first Karnopp test holds it too.
  ZAxisPlant resting(ZAxisParams{});
  resting.set_state(-120.0, 0.0, false);
  run(resting, 0.0, 1000);
  EXPECT_TRUE(resting.stuck());
  EXPECT_EQ(resting.position_mm(), -120.0);
}

TEST(ZAxisPlant, ServoOffHeadSagsOnlyWhenPushedPastStiction) {
  // u = 0 (servo off): K u + d_g + d_cut = -1 + push.
  ZAxisPlant below(ZAxisParams{});
  below.set_state(-120.0, 0.0, true);
  run(below, 0.0, 100'000, -2.99);  // |-3.99| <= 4
  EXPECT_EQ(below.position_mm(), -120.0) << "a push of 2.99 mm/s down plus the weight is still below f_s";
  ZAxisPlant past(ZAxisParams{});
  past.set_state(-120.0, 0.0, true);
  run(past, 0.0, 100'000, -3.01);  // |-4.01| > 4
  EXPECT_LT(past.position_mm(), -120.0) << "pushed past f_s, the head sags";
  // Upward, gravity helps to hold it: a push of +4.99 leaves 3.99.
  ZAxisPlant up(ZAxisParams{});
  up.set_state(-120.0, 0.0, true);
  run(up, 0.0, 100'000, 4.99);
  EXPECT_EQ(up.position_mm(), -120.0);
  run(up, 0.0, 100'000, 5.01);
  EXPECT_GT(up.position_mm(), -120.0);
}

TEST(ZAxisPlant, MovingHeadSettlesAtCommandPlusGravityMinusFriction) {
  // Down at u = -6: tau dv/dt = -6 - 1 + f_c - v, so v -> -5 mm/s.
  ZAxisPlant z(ZAxisParams{});
  z.set_state(-10.0, 0.0, true);
  run(z, -6.0, 50'000);  // 0.5 s = 55 tau
  EXPECT_NEAR(z.speed_mm_s(), -5.0, 1e-9);
}

TEST(ZAxisPlant, EndStopsStopTheHeadAndCountTheHit) {
  ZAxisPlant z(ZAxisParams{});
  z.set_state(-290.0, 0.0);
  run(z, -50.0, 200'000);  // 2 s toward the bottom at ~50 mm/s
  EXPECT_EQ(z.position_mm(), -305.0) << "bottom stop = travel bottom - overtravel";
  EXPECT_EQ(z.speed_mm_s(), 0.0);
  EXPECT_EQ(z.end_stop_hits(), 1u) << "one arrival, however long it is pressed";
  EXPECT_TRUE(z.beyond_travel());
  run(z, 20.0, 200'000);  // away, then up into the top stop
  run(z, 200.0, 300'000);
  EXPECT_EQ(z.position_mm(), 5.0);
  EXPECT_EQ(z.end_stop_hits(), 2u);
}

TEST(ZAxisPlant, TheBoardsHomeSwitchIsAtTheTopOfTheTravel) {
  const BoardParams board{};
  EXPECT_TRUE(board.home_switch(hal::Axis::z));
  EXPECT_EQ(board.home_mm(hal::Axis::z), ZAxisParams{}.travel_top_mm);
  EXPECT_EQ(board.home_side(hal::Axis::z), 1);  // actuated at and above it
  EXPECT_FALSE(board.home_switch(hal::Axis::x));
  EXPECT_FALSE(board.home_switch(hal::Axis::y));
}

}  // namespace
}  // namespace tnv::emu
