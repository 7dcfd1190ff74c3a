// Cutting where the tool is (reference plant "Stock, and cutting where the
// tool is"): engagement, feed per tooth, S3's force law and lag, its
// direction, the crash rule and the touch probe.
#include "emulator/cutting_at_tool.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "emulator/spindle_drive.hpp"
#include "emulator/substep_timing.hpp"

namespace tnv::emu {
namespace {

constexpr double kTop_mm = -150.0;

Scenario with_stock(double x_min, double x_max, double y_min, double y_max) {
  Scenario s;
  s.stock.x_min_mm = x_min;
  s.stock.x_max_mm = x_max;
  s.stock.y_min_mm = y_min;
  s.stock.y_max_mm = y_max;
  return s;
}

// The tool point moves as its speed says (the stock's height field takes
// what it passes: standing still with a speed it would meet nothing new).
// Returns where it ended.
ToolPointMotion run(CuttingAtTool& cut, ToolPointMotion at, double rpm, double seconds, double commanded_rpm = 6000.0) {
  const auto n = static_cast<std::uint64_t>(std::llround(seconds / kSubstep_s));
  for (std::uint64_t i = 0; i < n; ++i) {
    cut.advance(at, rpm, commanded_rpm, substep_time_s(i));
    at.x_mm += at.vx_mm_s * kSubstep_s;
    at.y_mm += at.vy_mm_s * kSubstep_s;
  }
  return at;
}

TEST(ToolMillingForce, SpecificForceComesFromTheS3ReferenceCut) {
  const Scenario s;
  // 150 N at a_p 1 mm, f_z 0.05 mm, D = 3/8", whatever K_c that takes.
  const double expected_kc = 150.0 / (1.0 * std::pow(0.05, 0.75) * std::pow(9.525, 0.25));
  EXPECT_NEAR(s.tool_cut.k_c_n_mm2, expected_kc, 1e-9 * expected_kc);
  EXPECT_EQ(s.tool.diameter_mm, 9.525);
  EXPECT_EQ(s.tool.flutes, 4);
  const ToolMillingForce force(s.tool_cut, s.tool, kSubstep_s);
  EXPECT_NEAR(force.steady_force_n(1.0, 0.05), 150.0, 1e-9);
  // The law's exponents: linear in a_p, f_z^0.75.
  EXPECT_NEAR(force.steady_force_n(2.0, 0.05), 300.0, 1e-9);
  EXPECT_NEAR(force.steady_force_n(1.0, 0.1), 150.0 * std::pow(2.0, 0.75), 1e-9);
  EXPECT_EQ(force.steady_force_n(0.0, 0.05), 0.0);
}

TEST(ToolMillingForce, FeedPerToothFromTableSpeedAndActualSpindleSpeed) {
  const Scenario s;
  const ToolMillingForce force(s.tool_cut, s.tool, kSubstep_s);
  // 4 flutes at 6000 rpm: 400 teeth/s; 20 mm/s -> 0.05 mm.
  EXPECT_NEAR(force.feed_per_tooth_mm(20.0, 6000.0), 0.05, 1e-15);
  EXPECT_NEAR(force.feed_per_tooth_mm(20.0, -6000.0), 0.05, 1e-15) << "either direction of rotation";
  EXPECT_NEAR(force.feed_per_tooth_mm(20.0, 3000.0), 0.10, 1e-15);
  EXPECT_EQ(force.feed_per_tooth_mm(0.0, 6000.0), 0.0);
  EXPECT_EQ(force.feed_per_tooth_mm(20.0, 0.0), s.tool_cut.max_feed_per_tooth_mm) << "capped, not infinite";
}

TEST(StockBlock, EngagementIsClampedDepthBelowTheTopWhereTheToolOverlapsTheStock) {
  const Scenario s = with_stock(0.0, 100.0, 0.0, 50.0);
  const StockBlock stock(s.stock);
  EXPECT_EQ(stock.engagement_mm(50.0, 25.0, kTop_mm + 0.5, s.tool), 0.0) << "above the top";
  EXPECT_DOUBLE_EQ(stock.engagement_mm(50.0, 25.0, kTop_mm - 1.0, s.tool), 1.0);
  EXPECT_EQ(stock.engagement_mm(50.0, 25.0, kTop_mm - 80.0, s.tool), s.tool.flute_length_mm) << "at most the flutes";
  // The tool's disc (radius 4.7625 mm) reaches the side x = 0 from x = -4.
  EXPECT_DOUBLE_EQ(stock.engagement_mm(-4.0, 25.0, kTop_mm - 1.0, s.tool), 1.0);
  EXPECT_EQ(stock.engagement_mm(-5.0, 25.0, kTop_mm - 1.0, s.tool), 0.0);
  EXPECT_EQ(stock.engagement_mm(50.0, 60.0, kTop_mm - 1.0, s.tool), 0.0);
  // Default: the whole table.
  const StockBlock everywhere(Scenario{}.stock);
  EXPECT_DOUBLE_EQ(everywhere.engagement_mm(-400.0, 300.0, kTop_mm - 2.0, s.tool), 2.0);
}

TEST(CuttingAtTool, ForceOpposesTheFeedThroughTheLag) {
  const Scenario s;
  CuttingAtTool cut(s, kSubstep_s);
  const ToolPointMotion at{.x_mm = 0.0, .y_mm = 0.0, .z_mm = kTop_mm - 1.0, .vx_mm_s = 20.0, .vy_mm_s = 0.0};
  const ToolPointMotion after = run(cut, at, 6000.0, 0.2);  // one T_f
  EXPECT_NEAR(cut.force().force_x_n(), -150.0 * (1.0 - std::exp(-1.0)), 1e-9) << "first-order lag, T_f = 0.2 s";
  run(cut, after, 6000.0, 2.8);
  EXPECT_NEAR(cut.force().force_x_n(), -150.0, 1e-4);
  EXPECT_NEAR(cut.force().force_y_n(), 0.0, 1e-12);
  EXPECT_NEAR(cut.force().force_n(), 150.0, 1e-4);
  EXPECT_NEAR(cut.force().disturbance_x_mm_s(), -1.5, 1e-6) << "F / 100 N per mm/s";
  EXPECT_EQ(cut.crashes().count(), 0u);
}

TEST(CuttingAtTool, DirectionFollowsAnyXyFeed) {
  const Scenario s;
  CuttingAtTool cut(s, kSubstep_s);
  // Down-left at 45 degrees, 20 mm/s: the force points up-right.
  const double v = 20.0 / std::sqrt(2.0);
  run(cut, ToolPointMotion{.z_mm = kTop_mm - 1.0, .vx_mm_s = -v, .vy_mm_s = -v}, 6000.0, 4.0);
  EXPECT_NEAR(cut.force().force_x_n(), 150.0 / std::sqrt(2.0), 1e-4);
  EXPECT_NEAR(cut.force().force_y_n(), 150.0 / std::sqrt(2.0), 1e-4);
  EXPECT_NEAR(cut.force().disturbance_y_mm_s(), 1.5 / std::sqrt(2.0), 1e-6);
}

TEST(CuttingAtTool, SlowerSpindleThickerChipMoreForce) {
  const Scenario s;
  CuttingAtTool cut(s, kSubstep_s);
  // Commanded 6000, actually 4000 (above half): no crash, f_z = 0.075 mm.
  run(cut, ToolPointMotion{.z_mm = kTop_mm - 1.0, .vx_mm_s = 20.0}, 4000.0, 4.0);
  EXPECT_NEAR(cut.force().force_n(), 150.0 * std::pow(1.5, 0.75), 1e-3);
  EXPECT_EQ(cut.crashes().count(), 0u);
}

// The force loads the spindle, the droop thickens the chip: the pair settles
// where n = 6000 - k_d F and F = 150 (6000 / n)^0.75.
TEST(CuttingAtTool, TheSpindlesDroopFeedsBackIntoTheChip) {
  const Scenario s;
  CuttingAtTool cut(s, kSubstep_s);
  SpindleDrive spindle(s.spindle);
  spindle.set_command_code(spindle.code_for_rpm(6000.0));
  for (int i = 0; i < 300'000; ++i) spindle.step();  // 3 s: at speed before the cut
  ToolPointMotion at{.z_mm = kTop_mm - 1.0, .vx_mm_s = 20.0};
  for (std::uint64_t i = 0; i < 600'000; ++i) {  // 6 s = 30 T_f
    cut.advance(at, spindle.speed_rpm(), spindle.commanded_rpm(), substep_time_s(i));
    at.x_mm += at.vx_mm_s * kSubstep_s;
    spindle.step(cut.force().force_n());
  }
  double n_rpm = 6000.0, f_n = 150.0;
  for (int k = 0; k < 50; ++k) {
    f_n = 150.0 * std::pow(6000.0 / n_rpm, 0.75);
    n_rpm = 6000.0 - 0.2 * f_n;
  }
  EXPECT_NEAR(spindle.speed_rpm(), n_rpm, 1e-3);
  EXPECT_NEAR(cut.force().force_n(), f_n, 1e-3);
  EXPECT_GT(cut.force().force_n(), 150.5) << "the drooped spindle cuts a thicker chip than at 6000 rpm";
  EXPECT_EQ(cut.crashes().count(), 0u);
}

TEST(CuttingAtTool, NoForceOutOfTheStockOrAtRest) {
  CuttingAtTool above(Scenario{}, kSubstep_s);
  run(above, ToolPointMotion{.z_mm = kTop_mm + 0.1, .vx_mm_s = 20.0}, 6000.0, 1.0);
  EXPECT_EQ(above.force().force_n(), 0.0);
  CuttingAtTool beside(with_stock(0.0, 100.0, 0.0, 100.0), kSubstep_s);
  run(beside, ToolPointMotion{.x_mm = -10.0, .y_mm = 50.0, .z_mm = kTop_mm - 1.0, .vy_mm_s = 20.0}, 6000.0, 1.0);
  EXPECT_EQ(beside.force().force_n(), 0.0);
  CuttingAtTool resting(Scenario{}, kSubstep_s);
  run(resting, ToolPointMotion{.z_mm = kTop_mm - 1.0}, 6000.0, 1.0);
  EXPECT_EQ(resting.force().force_n(), 0.0) << "no feed, no chip";
}

TEST(CuttingAtTool, EngagingWithASlowOrStoppedSpindleIsACrash) {
  CuttingAtTool cut(with_stock(0.0, 100.0, 0.0, 100.0), kSubstep_s);
  const ToolPointMotion outside{.x_mm = -20.0, .y_mm = 50.0, .z_mm = kTop_mm - 1.0, .vx_mm_s = 20.0};
  const ToolPointMotion inside{.x_mm = 10.0, .y_mm = 50.0, .z_mm = kTop_mm - 1.0, .vx_mm_s = 20.0};
  run(cut, outside, 0.0, 0.1, 0.0);
  EXPECT_EQ(cut.crashes().count(), 0u) << "a stopped spindle in the air is no crash";
  cut.advance(inside, 2999.0, 6000.0, 1.25);
  ASSERT_EQ(cut.crashes().count(), 1u) << "below 50 % of the commanded speed";
  EXPECT_EQ(cut.crashes().event(0).time_s, 1.25);
  EXPECT_EQ(cut.crashes().event(0).x_mm, 10.0);
  EXPECT_EQ(cut.crashes().event(0).z_mm, kTop_mm - 1.0);
  EXPECT_EQ(cut.crashes().event(0).spindle_rpm, 2999.0);
  const ToolPointMotion further = run(cut, inside, 2999.0, 0.1);  // on through uncut stock
  EXPECT_EQ(cut.crashes().count(), 1u) << "one crash per episode";
  cut.advance(further, 3000.0, 6000.0, 2.0);
  EXPECT_FALSE(cut.crashes().crashing()) << "exactly half the commanded speed is not below it";
  cut.advance(further, 0.0, 0.0, 2.5);
  EXPECT_EQ(cut.crashes().count(), 2u) << "a stopped, commanded-off spindle";
  cut.advance(outside, 0.0, 0.0, 2.6);
  // Back into uncut stock (its own cut at x = 10 is gone: stock_surface_test.cpp).
  cut.advance(ToolPointMotion{.x_mm = 30.0, .y_mm = 50.0, .z_mm = kTop_mm - 1.0, .vx_mm_s = 20.0}, -6000.0, 6000.0,
              2.7);
  EXPECT_EQ(cut.crashes().count(), 3u) << "turning against its command";
  EXPECT_EQ(cut.crashes().event(2).time_s, 2.7);
}

TEST(TouchProbe, TriggersOnTheTopFaceAndTheSides) {
  const Scenario s = with_stock(0.0, 100.0, 0.0, 50.0);
  const StockBlock stock(s.stock);
  const TouchProbe probe(s.probe, stock);
  EXPECT_FALSE(probe.triggered(50.0, 25.0, kTop_mm + 0.001));
  EXPECT_TRUE(probe.triggered(50.0, 25.0, kTop_mm)) << "touching the top face";
  EXPECT_TRUE(probe.triggered(50.0, 25.0, kTop_mm - 3.0)) << "pushed into it";
  EXPECT_FALSE(probe.triggered(-0.001, 25.0, kTop_mm - 10.0));
  EXPECT_TRUE(probe.triggered(0.0, 25.0, kTop_mm - 10.0)) << "touching the side x = x_min";
  EXPECT_TRUE(probe.triggered(100.0, 50.0, kTop_mm - 10.0)) << "an edge";
  EXPECT_FALSE(probe.triggered(50.0, 50.001, kTop_mm - 10.0));
  // A 1 mm stylus ball touches 1 mm earlier.
  const TouchProbe ball(ProbeParams{.tip_radius_mm = 1.0}, stock);
  EXPECT_TRUE(ball.triggered(50.0, 25.0, kTop_mm + 1.0));
  EXPECT_FALSE(ball.triggered(50.0, 25.0, kTop_mm + 1.01));
  EXPECT_TRUE(ball.triggered(-1.0, 25.0, kTop_mm - 10.0));
}

TEST(CuttingAtTool, ProbeInputFollowsTheToolPoint) {
  CuttingAtTool cut(Scenario{}, kSubstep_s);
  cut.advance(ToolPointMotion{.z_mm = kTop_mm + 1.0}, 0.0, 0.0, 0.0);
  EXPECT_FALSE(cut.probe_touches(0.0, 0.0, kTop_mm + 1.0));
  cut.advance(ToolPointMotion{.z_mm = kTop_mm}, 0.0, 0.0, 0.0);
  EXPECT_TRUE(cut.probe_touches(0.0, 0.0, kTop_mm));
  EXPECT_EQ(cut.crashes().count(), 0u) << "touching is not engaging (a_p = 0)";
}

TEST(CuttingAtTool, ToolPointIsTheNoseMinusTheToolLength) {
  const ToolParams tool{};
  EXPECT_EQ(tool_point_z_mm(0.0, tool), -125.0);
  EXPECT_EQ(tool_point_z_mm(-30.0, ToolParams{.length_mm = 100.0}), -130.0);
}

}  // namespace
}  // namespace tnv::emu
