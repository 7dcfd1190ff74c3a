// Ball-screw compensation: half the backlash in the direction of travel,
// reached at the stated rate, kept while holding, swapped at a reversal;
// the cumulative lead error inverted exactly; the per-turn table periodic
// and interpolated; off is exactly nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "firmware/compensation/screw_compensation.hpp"

namespace tnv::fw {
namespace {

constexpr double kTick_s = 1e-3;

TEST(ScrewCompensation, OffAddsExactlyNothing) {
  ScrewCompensator comp;
  const ScrewCompensation off{};
  for (double x : {0.0, 6.0, -3.25, 123.456}) {
    const auto o = comp.advance(off, x, x + 0.002, kTick_s);
    EXPECT_EQ(o.now_mm, 0.0);
    EXPECT_EQ(o.next_mm, 0.0);
  }
}

TEST(ScrewCompensation, HalfTheBacklashEachWayAtTheStatedRate) {
  const ScrewCompensation c{0.010, 1.0, 0.0};  // 10 um, 1 mm/s: 5 um takes 5 ticks
  ScrewCompensator comp;
  // At rest after power-up: the lash is assumed centred, no offset.
  EXPECT_EQ(comp.advance(c, 0.0, 0.0, kTick_s).next_mm, 0.0);
  EXPECT_EQ(comp.direction(), 0);
  double x = 0.0;
  std::vector<double> offsets;
  for (int k = 0; k < 8; ++k, x += 0.002) offsets.push_back(comp.advance(c, x, x + 0.002, kTick_s).next_mm);
  EXPECT_EQ(comp.direction(), 1);
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(offsets[static_cast<std::size_t>(k)], 0.001 * (k + 1), 1e-15) << k;
  EXPECT_NEAR(offsets.back(), 0.005, 1e-15);
  // Holding keeps the direction and the offset.
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(comp.advance(c, x, x, kTick_s).next_mm, 0.005, 1e-15);
  EXPECT_EQ(comp.direction(), 1);
  // A reversal swaps it, 10 um at 1 um per tick; "now" is last tick's "next".
  double previous_next = 0.005;
  for (int k = 0; k < 12; ++k, x -= 0.002) {
    const auto o = comp.advance(c, x, x - 0.002, kTick_s);
    EXPECT_NEAR(o.now_mm, previous_next, 1e-15);
    EXPECT_NEAR(o.next_mm, std::max(-0.005, 0.005 - 0.001 * (k + 1)), 1e-15) << k;
    previous_next = o.next_mm;
  }
  EXPECT_EQ(comp.direction(), -1);
  comp.reset();
  EXPECT_EQ(comp.direction(), 0);
  EXPECT_EQ(comp.next_offset_mm(), 0.0);
}

TEST(ScrewCompensation, TheLeadErrorIsInvertedExactly) {
  const ScrewCompensation c{0.0, 1.0, 60.0};  // the table moves 1.00006 mm per motor mm
  ScrewCompensator comp;
  for (double x : {0.0, 12.0, -250.0}) {
    const auto o = comp.advance(c, x, x, kTick_s);
    const double motor_mm = x + o.now_mm;
    EXPECT_NEAR(motor_mm * (1.0 + 60e-6), x, 1e-12) << x;
  }
}

TEST(ScrewCompensation, OutOfRangeAndNonFiniteValuesAreRefusedByName) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(validate(ScrewCompensation{}).ok);
  EXPECT_TRUE(validate(ScrewCompensation{0.2, 100.0, -1000.0}).ok);
  const std::pair<ScrewCompensation, const char*> bad[] = {
      {{-0.001, 1.0, 0.0}, "backlash_mm"}, {{0.3, 1.0, 0.0}, "backlash_mm"},   {{nan, 1.0, 0.0}, "backlash_mm"},
      {{0.0, 0.0, 0.0}, "backlash_rate_mm_s"}, {{0.0, nan, 0.0}, "backlash_rate_mm_s"},
      {{0.0, 1.0, 1001.0}, "lead_um_per_m"},   {{0.0, 1.0, nan}, "lead_um_per_m"}};
  for (const auto& [c, field] : bad) {
    const ParamCheck check = validate(c);
    EXPECT_FALSE(check.ok) << field;
    EXPECT_STREQ(check.field, field);
  }
}

ScrewCompensation with_turn_table() {
  ScrewCompensation c;
  c.turn_period_mm = 10.0;
  for (std::size_t j = 0; j < kTurnErrorPoints; ++j) c.turn_error_mm[j] = 0.001 * static_cast<double>(j);  // 0 .. 15 um
  return c;
}

TEST(ScrewCompensation, TheTurnTableIsPeriodicAndLinearBetweenItsPoints) {
  const ScrewCompensation c = with_turn_table();
  // Points at j * 10 / 16 = j * 0.625 mm, in any turn, either side of zero.
  for (const double turn_mm : {0.0, 10.0, -10.0, 250.0, -250.0}) {
    EXPECT_NEAR(turn_error_mm(c, turn_mm + 3 * 0.625), 0.003, 1e-12) << turn_mm;
    EXPECT_NEAR(turn_error_mm(c, turn_mm + 3.5 * 0.625), 0.0035, 1e-12) << turn_mm;
    // Between the last point and the next turn's first: 15 um back to 0.
    EXPECT_NEAR(turn_error_mm(c, turn_mm + 15.5 * 0.625), 0.0075, 1e-12) << turn_mm;
  }
}

TEST(ScrewCompensation, TheMotorGoesWhereTheTableMeetsTheReference) {
  // A smooth per-turn error (4 um, one sine per turn), tabulated at its 16 points.
  ScrewCompensation c;
  c.lead_um_per_m = 60.0;
  for (std::size_t j = 0; j < kTurnErrorPoints; ++j)
    c.turn_error_mm[j] = 0.004 * std::sin(2.0 * 3.141592653589793 * static_cast<double>(j) / 16.0);
  ScrewCompensator comp;
  for (double x : {0.0, 1.3, 6.0, -7.77, 42.0}) {
    const auto o = comp.advance(c, x, x, kTick_s);
    const double p = x + o.now_mm;  // the motor position the axis is sent to
    const double table_mm = p * (1.0 + 60e-6) + turn_error_mm(c, p);
    EXPECT_NEAR(table_mm, x, 2e-5) << x;  // one fixed-point step: within 0.02 um
  }
}

TEST(ScrewCompensation, TurnTableOutOfRangeOrNanIsRefusedByName) {
  ScrewCompensation c = with_turn_table();
  EXPECT_TRUE(validate(c).ok);
  c.turn_error_mm[7] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_STREQ(validate(c).field, "turn_error_mm");
  c.turn_error_mm[7] = 0.2;
  EXPECT_STREQ(validate(c).field, "turn_error_mm");
  c = with_turn_table();
  c.turn_period_mm = 0.0;
  EXPECT_STREQ(validate(c).field, "turn_period_mm");
  EXPECT_FALSE(c == with_turn_table());
}

}  // namespace
}  // namespace tnv::fw
