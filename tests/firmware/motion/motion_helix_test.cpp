// Z in the motion core: lines in XYZ keep Z's own limits, and a helix (an
// arc in XY with Z moving in step with its angle) keeps its radius, its
// pitch and every axis' limits.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "firmware/motion/segment_geometry.hpp"
#include "tests/firmware/motion/motion_run.hpp"

namespace tnv::fw::motion {
namespace {

constexpr std::size_t kZ = hal::index(hal::Axis::z);

TEST(MotionHelix, AHelixsLengthIncludesZAndItsPointsClimbWithTheAngle) {
  const PlanePoint start{10.0, 0.0, -1.0};
  SegmentGeometry g;
  // Three quarters of a turn ccw about the origin, 3 mm down.
  ASSERT_EQ(prepare(arc_to(false, {0.0, -10.0, -4.0}, {0.0, 0.0, -1.0}, 10.0), start, MotionLimits{}, g),
            SegmentRefusal::none);
  const double plane_mm = 10.0 * 1.5 * std::numbers::pi;
  EXPECT_NEAR(g.length_mm, std::hypot(plane_mm, 3.0), 1e-9);
  EXPECT_NEAR(g.unit_start[kZ], -3.0 / g.length_mm, 1e-12);
  EXPECT_NEAR(std::hypot(std::hypot(g.unit_start[0], g.unit_start[1]), g.unit_start[kZ]), 1.0, 1e-12);
  const PlanePoint half = g.point_at(0.5 * g.length_mm);
  EXPECT_NEAR(half[kZ], -2.5, 1e-12);
  EXPECT_NEAR(std::atan2(half[1], half[0]), 0.75 * std::numbers::pi, 1e-12);
  EXPECT_EQ(g.point_at(g.length_mm)[kZ], -4.0);

  // An arc in the plane is what it was: no Z, the plane's length bit for bit.
  ASSERT_EQ(prepare(arc_to(false, {0.0, -10.0, -1.0}, {0.0, 0.0, -1.0}, 10.0), start, MotionLimits{}, g),
            SegmentRefusal::none);
  EXPECT_EQ(g.length_mm, 0.5 * (10.0 + 10.0) * 1.5 * std::numbers::pi);
  EXPECT_EQ(g.unit_start[kZ], 0.0);
}

TEST(MotionHelix, LinesInXyzKeepZsOwnSpeedAndSoftLimits) {
  MotionLimits limits;
  limits.axis[kZ].speed_mm_s = 5.0;
  limits.axis[kZ].position_min_mm = -300.0;
  limits.axis[kZ].position_max_mm = 0.0;
  SegmentGeometry g;
  const PlanePoint start{0.0, 0.0, -10.0};
  EXPECT_EQ(prepare(line_to({0.0, 0.0, -20.0}, 5.0), start, limits, g), SegmentRefusal::none);
  EXPECT_EQ(prepare(line_to({0.0, 0.0, -20.0}, 5.5), start, limits, g), SegmentRefusal::feed_above_limit)
      << "a plunge faster than Z's own speed";
  // 45 degrees in XZ: Z's share of the feed is its limit at 5 sqrt(2).
  EXPECT_EQ(prepare(line_to({10.0, 0.0, -20.0}, 7.0), start, limits, g), SegmentRefusal::none);
  EXPECT_EQ(prepare(line_to({10.0, 0.0, -20.0}, 7.2), start, limits, g), SegmentRefusal::feed_above_limit);
  EXPECT_EQ(prepare(line_to({0.0, 0.0, 1.0}, 2.0), start, limits, g), SegmentRefusal::outside_workspace)
      << "above Z's top";
  EXPECT_EQ(prepare(line_to({0.0, 0.0, -301.0}, 2.0), start, limits, g), SegmentRefusal::outside_workspace);
}

TEST(MotionHelix, AHelixRunKeepsItsRadiusPitchAndEveryAxisLimit) {
  MotionLimits limits;
  limits.axis[kZ].accel_mm_s2 = 0.25 * limits.axis[0].accel_mm_s2;  // Z slower than the plane
  MotionInterpolator m;
  ASSERT_STREQ(m.configure(limits, {10.0, 0.0, 0.0}), "");
  // Two full turns down 2 mm each (pitch 2 mm), a plunge before and a retract after.
  const std::vector<Segment> program = {
      line_to({10.0, 0.0, -1.0}, 5.0),
      arc_to(false, {10.0, 0.0, -3.0}, {0.0, 0.0, 0.0}, 20.0),
      arc_to(false, {10.0, 0.0, -5.0}, {0.0, 0.0, 0.0}, 20.0),
      line_to({10.0, 0.0, 0.0}, 10.0)};
  const test::MotionRun run = test::run_program(m, program, 2'000'000, [](std::size_t, MotionInterpolator&) {});
  ASSERT_FALSE(run.position_mm.empty());
  EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(run.jerk_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(run.speed_ratio_max, 1.0 + 1e-6);
  EXPECT_EQ(m.stats().follower.guard_failures, 0u);
  // From below -1.2 mm to -4.8 mm the reference is on the helix: radius 10, and Z = -1 - 2 * turns.
  const test::HelixFit fit = test::fit_helix(run.position_mm, 0, 1, kZ, 10.0, -1.0, 2.0, -1.2, -4.8);
  EXPECT_GT(fit.samples, 2000u) << "two turns of 62.8 mm at 20 mm/s";
  EXPECT_LE(fit.radius_worst_mm, limits.path_tolerance_mm) << fit.radius_worst_mm * 1e3 << " um radius error";
  EXPECT_LE(fit.pitch_worst_mm, limits.path_tolerance_mm) << fit.pitch_worst_mm * 1e3 << " um off the helix in Z";
  EXPECT_NEAR(run.position_mm.back()[kZ], 0.0, 1e-9);
}

}  // namespace
}  // namespace tnv::fw::motion
