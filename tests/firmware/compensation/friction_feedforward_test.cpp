// Friction feed-forward (issue 7, item 3): the Stribeck level, the rule at
// velocity reversals, validation, and that it is off by default.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "firmware/compensation/friction_feedforward.hpp"
#include "firmware/tick/firmware_config.hpp"

namespace tnv::fw {
namespace {

FrictionFeedForward on() {
  FrictionFeedForward ff;
  ff.enabled = true;
  ff.coulomb_mm_s = 1.5;
  ff.stiction_mm_s = 3.0;
  ff.stribeck_mm_s = 0.1;
  ff.gain = 1.0;
  return ff;
}

TEST(FrictionFeedForward, OffByDefaultEverywhere) {
  EXPECT_FALSE(FrictionFeedForward{}.enabled);
  const FirmwareConfig config = default_firmware_config();
  for (const AxisConfig& a : config.axis) EXPECT_FALSE(a.friction.enabled);
  EXPECT_EQ(friction_feedforward_mm_s(FrictionFeedForward{}, 2.0, 2.0), 0.0);
}

TEST(FrictionFeedForward, CoulombAtSpeedStictionAtZero) {
  const FrictionFeedForward ff = on();
  EXPECT_NEAR(friction_feedforward_mm_s(ff, 2.0, 2.0), 1.5, 1e-12) << "mm/s at +2 mm/s";
  EXPECT_NEAR(friction_feedforward_mm_s(ff, -2.0, -2.0), -1.5, 1e-12) << "mm/s at -2 mm/s";
  EXPECT_NEAR(stribeck_level_mm_s(ff, 0.0), 3.0, 1e-12);
  EXPECT_NEAR(stribeck_level_mm_s(ff, 0.1), 1.5 + 1.5 * std::exp(-1.0), 1e-12);
}

TEST(FrictionFeedForward, GainAndFractionScaleTheCommand) {
  FrictionFeedForward ff = on();
  ff.gain = 2.0;
  ff.fraction = 0.5;
  EXPECT_NEAR(friction_feedforward_mm_s(ff, 5.0, 5.0), 1.5 * 0.5 / 2.0, 1e-12);
}

TEST(FrictionFeedForward, ReversalTakesTheDirectionTheReferenceIsGoing) {
  const FrictionFeedForward ff = on();
  // Passing through zero from + to -: the mean is 0, the change is negative.
  EXPECT_NEAR(friction_feedforward_mm_s(ff, 0.001, -0.001), -3.0, 1e-9);
  EXPECT_NEAR(friction_feedforward_mm_s(ff, -0.001, 0.001), 3.0, 1e-9);
  // Turning from rest: the way it is about to move.
  EXPECT_GT(friction_feedforward_mm_s(ff, 0.0, 1e-4), 2.9);
  // At rest: nothing (a holding axis is not pushed against its stiction).
  EXPECT_EQ(friction_feedforward_mm_s(ff, 0.0, 0.0), 0.0);
}

TEST(FrictionFeedForward, ValidationNamesTheField) {
  FrictionFeedForward ff = on();
  EXPECT_TRUE(validate(ff).ok);
  ff.coulomb_mm_s = std::numeric_limits<double>::quiet_NaN();
  EXPECT_STREQ(validate(ff).field, "coulomb_mm_s");
  ff = on();
  ff.stiction_mm_s = 1.0;  // below f_c
  EXPECT_STREQ(validate(ff).field, "stiction_mm_s");
  ff = on();
  ff.stribeck_mm_s = 0.0;
  EXPECT_STREQ(validate(ff).field, "stribeck_mm_s");
  ff = on();
  ff.gain = -1.0;
  EXPECT_STREQ(validate(ff).field, "gain");
  ff = on();
  ff.fraction = 2.0;
  EXPECT_STREQ(validate(ff).field, "fraction");
  ff = on();
  ff.gain = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(validate(ff).ok);
}

TEST(FrictionFeedForward, ConfigValidationRejectsABadSetWhole) {
  FirmwareConfig config = default_firmware_config();
  config.axis[1].friction = on();
  config.axis[1].friction.stribeck_mm_s = -0.1;
  const ConfigError e = validate(config);
  EXPECT_FALSE(e.ok());
  EXPECT_STREQ(e.section, "axis y: friction feed-forward");
  EXPECT_STREQ(e.field, "stribeck_mm_s");
}

}  // namespace
}  // namespace tnv::fw
