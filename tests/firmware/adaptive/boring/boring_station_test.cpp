// The planner as the node runs it (boring_station.hpp): plain data in, plain
// data out, the same infeeds as one planner object kept over the parts, and
// nothing changed by a refused part.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "firmware/adaptive/boring/boring_station.hpp"

namespace tnv::fw {
namespace {

constexpr double kStep = 2e-5;  // BORE_INFEED's grid

double station_deflection(double c, double a, double b, double s, double l) {
  return c * std::pow(s, a) * std::pow(l, b);
}

BoringStationSettings on_settings() {
  BoringStationSettings s;
  s.enabled = true;
  return s;
}

TEST(BoringStation, GivesTheInfeedsOfOnePlannerKeptOverThePartsOnTheGrid) {
  const BoringStationSettings settings = on_settings();
  BoringStationState state;
  BoringInfeedPlanner direct(planner_params(settings));
  double c = 0.0871, a = 0.5025, b = 0.2676;
  for (int part = 1; part <= 30; ++part) {
    if (part == 11) {  // S4's large change
      c = 0.15;
      a = 0.7;
      b = 0.4;
    }
    const std::array<double, 2> told = current_infeeds_mm_rev(settings, state, kStep);
    std::array<double, 2> errors{};
    BoreMeasurement m[2];
    for (int i = 0; i < 2; ++i) {
      const double l = i == 0 ? settings.top_overhang_mm : settings.bottom_overhang_mm;
      const double s = on_infeed_grid(direct.infeed(l).infeed_mm_rev, kStep);
      ASSERT_EQ(told[static_cast<std::size_t>(i)], s) << "part " << part << " position " << i;
      const double d = station_deflection(c, a, b, s, l) + 0.004 * std::sin(part * 1.7 + i);
      errors[static_cast<std::size_t>(i)] = bore_error_from_deflection_mm(d, settings.d0_mm, settings.force_angle_deg);
      m[i] = {l, s, errors[static_cast<std::size_t>(i)]};
    }
    const BoringStationAnswer ans = record_bored_part(settings, state, errors, kStep);
    const BoringPartReport rep = direct.record_part(m);
    ASSERT_TRUE(ans.check.ok) << ans.check.field << ": " << ans.check.reason;
    ASSERT_TRUE(rep.check.ok);
    EXPECT_EQ(ans.report.startup, rep.startup);
    EXPECT_EQ(ans.report.reset, rep.reset) << "part " << part;
    EXPECT_EQ(ans.report.out_of_band, rep.out_of_band);
    EXPECT_EQ((ans.out_of_band[0] ? 1 : 0) + (ans.out_of_band[1] ? 1 : 0), rep.out_of_band);
    EXPECT_TRUE(state.planner == direct.state()) << "part " << part;
    for (double s : state.infeed_mm_rev) EXPECT_EQ(std::round(s / kStep) * kStep, s) << "on the grid";
  }
  EXPECT_GE(direct.resets(), 1) << "the large change at part 11";
}

TEST(BoringStation, BeforeStartUpThePartIsCutAtS0AndRestartGoesBackThere) {
  BoringStationSettings settings = on_settings();
  settings.s0_mm_rev = 0.31;
  BoringStationState state;
  EXPECT_EQ(current_infeeds_mm_rev(settings, state, kStep)[0], on_infeed_grid(0.31, kStep));
  ASSERT_TRUE(record_bored_part(settings, state, {0.05, 0.17}, kStep).check.ok);
  EXPECT_TRUE(state.planner.started);
  EXPECT_NE(current_infeeds_mm_rev(settings, state, kStep)[1], on_infeed_grid(0.31, kStep));
  restart(state);
  EXPECT_TRUE(state == BoringStationState{});
  EXPECT_EQ(current_infeeds_mm_rev(settings, state, kStep)[1], on_infeed_grid(0.31, kStep));
}

TEST(BoringStation, ARefusedPartChangesNothingAndNamesTheReading) {
  const BoringStationSettings settings = on_settings();
  BoringStationState state;
  // Start-up: a bore error that means a deflection <= 0 has no logarithm (eq. (10)).
  const double no_deflection = bore_error_from_deflection_mm(-0.001, settings.d0_mm, settings.force_angle_deg);
  BoringStationAnswer a = record_bored_part(settings, state, {0.05, no_deflection}, kStep);
  EXPECT_FALSE(a.check.ok);
  EXPECT_EQ(a.position, kBoringBottom);
  EXPECT_TRUE(state == BoringStationState{});
  ASSERT_TRUE(record_bored_part(settings, state, {0.05, 0.17}, kStep).check.ok);
  const BoringStationState started = state;
  a = record_bored_part(settings, state, {std::numeric_limits<double>::quiet_NaN(), 0.0}, kStep);
  EXPECT_FALSE(a.check.ok);
  EXPECT_EQ(a.position, kBoringTop);
  EXPECT_TRUE(state == started);
  // After start-up a deflection <= 0 is counted for the band, not fitted: accepted.
  a = record_bored_part(settings, state, {0.0, no_deflection}, kStep);
  EXPECT_TRUE(a.check.ok);
  EXPECT_TRUE(a.out_of_band[kBoringBottom]);
  EXPECT_EQ(a.report.skipped, 1);
  // A damaged state is refused, not used.
  BoringStationState damaged = state;
  damaged.planner.covariance(0, 0) = 1.5;  // P never grows above P0 = I
  const BoringStationState kept = damaged;
  EXPECT_FALSE(record_bored_part(settings, damaged, {0.0, 0.0}, kStep).check.ok);
  EXPECT_TRUE(damaged == kept) << "nothing written";
}

TEST(BoringStation, SettingsAreCheckedUnderTheirOwnNames) {
  BoringStationSettings s = on_settings();
  EXPECT_TRUE(validate(s).ok);
  s.bottom_overhang_mm = s.top_overhang_mm + 0.5;
  EXPECT_STREQ(validate(s).field, "bottom_overhang_mm") << "eq. (10) needs two overhangs";
  s = on_settings();
  s.s0_mm_rev = 2.0;
  EXPECT_STREQ(validate(s).field, "s0_mm_rev");
  s = on_settings();
  s.force_angle_deg = 90.0;
  EXPECT_STREQ(validate(s).field, "force_angle_deg");
  s = on_settings();
  s.reset_after = 0;
  EXPECT_STREQ(validate(s).field, "reset_after");
  // The top may be the longer overhang: the model's range is the span between them.
  s = on_settings();
  s.top_overhang_mm = 310.0;
  s.bottom_overhang_mm = 40.0;
  EXPECT_TRUE(validate(s).ok);
  EXPECT_EQ(planner_params(s).overhang_min_mm, 40.0);
}

TEST(BoringStation, TheInfeedsOfAStateAreZeroBeforeStartUpAndPositiveAfter) {
  BoringStationState s;
  EXPECT_TRUE(validate(s).ok);
  s.infeed_mm_rev[0] = 0.1;
  EXPECT_FALSE(validate(s).ok) << "told infeeds without a start-up part";
  s = BoringStationState{};
  ASSERT_TRUE(record_bored_part(on_settings(), s, {0.05, 0.17}, kStep).check.ok);
  EXPECT_TRUE(validate(s).ok);
  s.infeed_mm_rev[1] = 0.0;
  EXPECT_FALSE(validate(s).ok);
  s.infeed_mm_rev[1] = 2.5;
  EXPECT_FALSE(validate(s).ok);
}

}  // namespace
}  // namespace tnv::fw
