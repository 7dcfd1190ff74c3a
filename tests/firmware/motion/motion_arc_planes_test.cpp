// Arcs in the ZX (G18) and YZ (G19) planes: the same arc as in XY, measured
// in the plane's two axes (counter-clockwise from the first towards the
// second), the third axis moving with the angle (a helix). Each keeps its
// radius, its pitch and every axis' limits, as the XY helix does
// (motion_helix_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "firmware/motion/segment_geometry.hpp"
#include "tests/firmware/motion/motion_run.hpp"

namespace tnv::fw::motion {
namespace {

constexpr std::size_t kX = hal::index(hal::Axis::x);
constexpr std::size_t kY = hal::index(hal::Axis::y);
constexpr std::size_t kZ = hal::index(hal::Axis::z);

// The axis beyond the plane.
std::size_t helix_axis(ArcPlane plane) {
  const PlaneAxes p = plane_axes(plane);
  std::size_t h = 0;
  while (in_plane(p, h)) ++h;
  return h;
}

// A point from the plane's two coordinates and the helix axis'.
PlanePoint at(ArcPlane plane, double first, double second, double third) {
  const PlaneAxes p = plane_axes(plane);
  PlanePoint out{};
  out[p.first] = first;
  out[p.second] = second;
  out[helix_axis(plane)] = third;
  return out;
}

TEST(MotionArcPlanes, PlanesAreRs274sAxisOrders) {
  EXPECT_EQ(plane_axes(ArcPlane::xy).first, kX);
  EXPECT_EQ(plane_axes(ArcPlane::xy).second, kY);
  EXPECT_EQ(plane_axes(ArcPlane::zx).first, kZ);  // G18: counter-clockwise from Z towards X, seen from +Y
  EXPECT_EQ(plane_axes(ArcPlane::zx).second, kX);
  EXPECT_EQ(plane_axes(ArcPlane::yz).first, kY);  // G19: from Y towards Z, seen from +X
  EXPECT_EQ(plane_axes(ArcPlane::yz).second, kZ);
  EXPECT_EQ(helix_axis(ArcPlane::zx), kY);
  EXPECT_EQ(helix_axis(ArcPlane::yz), kX);
}

TEST(MotionArcPlanes, AG18QuarterTurnsFromZTowardsXAndItsHelixAxisClimbsWithTheAngle) {
  // Counter-clockwise a quarter about the origin from Z = 10 to X = 10, Y from 0 to -3.
  SegmentGeometry g;
  ASSERT_EQ(prepare(arc_to(false, {10.0, -3.0, 0.0}, {0.0, 0.0, 0.0}, 10.0, 0, ArcPlane::zx), {0.0, 0.0, 10.0},
                    MotionLimits{}, g),
            SegmentRefusal::none);
  const double plane_mm = 10.0 * 0.5 * std::numbers::pi;
  EXPECT_NEAR(g.length_mm, std::hypot(plane_mm, 3.0), 1e-9);
  EXPECT_NEAR(g.sweep_rad, 0.5 * std::numbers::pi, 1e-12);
  // Leaves Z = 10 towards +X, Y going down; the tangent is a unit vector in 3-D.
  EXPECT_NEAR(g.unit_start[kX], plane_mm / g.length_mm, 1e-12);
  EXPECT_NEAR(g.unit_start[kZ], 0.0, 1e-12);
  EXPECT_NEAR(g.unit_start[kY], -3.0 / g.length_mm, 1e-12);
  EXPECT_NEAR(g.unit_end[kZ], -plane_mm / g.length_mm, 1e-12);
  const PlanePoint half = g.point_at(0.5 * g.length_mm);
  EXPECT_NEAR(half[kX], 10.0 * std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(half[kZ], 10.0 * std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(half[kY], -1.5, 1e-12);
  EXPECT_EQ(g.point_at(g.length_mm), (PlanePoint{10.0, -3.0, 0.0}));

  // G19 clockwise: from Y = 10 towards -Z, X along.
  ASSERT_EQ(prepare(arc_to(true, {2.0, 0.0, -10.0}, {0.0, 0.0, 0.0}, 10.0, 0, ArcPlane::yz), {0.0, 10.0, 0.0},
                    MotionLimits{}, g),
            SegmentRefusal::none);
  EXPECT_NEAR(g.sweep_rad, -0.5 * std::numbers::pi, 1e-12);
  EXPECT_LT(g.unit_start[kZ], 0.0);
  EXPECT_GT(g.unit_start[kX], 0.0);
}

TEST(MotionArcPlanes, AnArcOutsideXyChecksItsPlanesRadiusAndEverySoftLimitOnTheWay) {
  MotionLimits limits;
  limits.axis[kZ].position_min_mm = -100.0;
  limits.axis[kZ].position_max_mm = 0.0;
  SegmentGeometry g;
  // A G18 half circle from X = -5 to X = 5 at Z = -3: ends within Z's travel, its top (Z = +2) above it.
  // Counter-clockwise from Z towards X, from X = -5 it rises through Z = +2.
  EXPECT_EQ(prepare(arc_to(false, {5.0, 0.0, -3.0}, {0.0, 0.0, -3.0}, 10.0, 0, ArcPlane::zx), {-5.0, 0.0, -3.0},
                    limits, g),
            SegmentRefusal::outside_workspace);
  // Clockwise it dips to Z = -8: inside.
  EXPECT_EQ(prepare(arc_to(true, {5.0, 0.0, -3.0}, {0.0, 0.0, -3.0}, 10.0, 0, ArcPlane::zx), {-5.0, 0.0, -3.0},
                    limits, g),
            SegmentRefusal::none);
  EXPECT_NEAR(g.point_at(0.5 * g.length_mm)[kZ], -8.0, 1e-12);
  // The radius is measured in the arc's plane: Y is the helix' axis in G18, not part of the radius.
  EXPECT_EQ(prepare(arc_to(true, {5.0, 40.0, -3.0}, {0.0, 0.0, -3.0}, 10.0, 0, ArcPlane::zx), {-5.0, 0.0, -3.0},
                    limits, g),
            SegmentRefusal::none);
  EXPECT_EQ(prepare(arc_to(true, {5.0, 0.0, -2.0}, {0.0, 0.0, -3.0}, 10.0, 0, ArcPlane::zx), {-5.0, 0.0, -3.0},
                    limits, g),
            SegmentRefusal::arc_radius_mismatch);
  // A plane value that is none of the three is refused, and `g` is left as it was.
  const SegmentGeometry before = g;
  EXPECT_EQ(prepare(arc_to(false, {5.0, 0.0, -3.0}, {0.0, 0.0, -3.0}, 10.0, 0, static_cast<ArcPlane>(3)),
                    {-5.0, 0.0, -3.0}, limits, g),
            SegmentRefusal::bad_kind);
  EXPECT_EQ(g.length_mm, before.length_mm);
  // The queue refuses it and stays as it was.
  MotionInterpolator m;
  ASSERT_STREQ(m.configure(limits, {-5.0, 0.0, -3.0}), "");
  EXPECT_EQ(m.push(arc_to(false, {5.0, 0.0, -3.0}, {0.0, 0.0, -3.0}, 10.0, 0, static_cast<ArcPlane>(200))),
            SegmentRefusal::bad_kind);
  EXPECT_EQ(m.queued(), 0u);
}

// Two full turns of radius 10 with a pitch of 2 mm along the helix axis, a
// plunge along it before and a retract after; the helix axis slower than
// the others, one plane axis slower again.
class MotionArcPlaneHelix : public ::testing::TestWithParam<ArcPlane> {};

TEST_P(MotionArcPlaneHelix, KeepsItsRadiusPitchAndEveryAxisLimit) {
  const ArcPlane plane = GetParam();
  const PlaneAxes pa = plane_axes(plane);
  const std::size_t h = helix_axis(plane);
  MotionLimits limits;
  limits.axis[h].accel_mm_s2 = 0.25 * limits.axis[pa.first].accel_mm_s2;
  limits.axis[pa.second].speed_mm_s = 30.0;
  limits.axis[pa.second].jerk_mm_s3 = 0.5 * limits.axis[pa.first].jerk_mm_s3;
  MotionInterpolator m;
  ASSERT_STREQ(m.configure(limits, at(plane, 10.0, 0.0, 0.0)), "");
  const PlanePoint centre = at(plane, 0.0, 0.0, 0.0);
  const std::vector<Segment> program = {
      line_to(at(plane, 10.0, 0.0, -1.0), 5.0),
      arc_to(false, at(plane, 10.0, 0.0, -3.0), centre, 20.0, 0, plane),
      arc_to(false, at(plane, 10.0, 0.0, -5.0), centre, 20.0, 0, plane),
      line_to(at(plane, 10.0, 0.0, 0.0), 10.0)};
  const test::MotionRun run = test::run_program(m, program);
  ASSERT_FALSE(run.position_mm.empty());
  EXPECT_LE(run.accel_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(run.jerk_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(run.speed_ratio_max, 1.0 + 1e-6);
  EXPECT_GT(run.accel_ratio_max, 0.5) << "the binding axis uses its limit";
  EXPECT_EQ(m.stats().follower.guard_failures, 0u);
  // Below -1.2 and above -4.8 the reference is on the helix: radius 10, height -1 - 2 turns.
  const test::HelixFit fit = test::fit_helix(run.position_mm, pa.first, pa.second, h, 10.0, -1.0, 2.0, -1.2, -4.8);
  EXPECT_GT(fit.samples, 2000u) << "two turns of 62.8 mm at 20 mm/s";
  EXPECT_GT(fit.turned_rad, 3.5 * std::numbers::pi) << "counter-clockwise in the plane's own sense";
  EXPECT_LE(fit.radius_worst_mm, limits.path_tolerance_mm) << fit.radius_worst_mm * 1e3 << " um radius error";
  EXPECT_LE(fit.pitch_worst_mm, limits.path_tolerance_mm) << fit.pitch_worst_mm * 1e3 << " um off the helix";
  EXPECT_NEAR(run.position_mm.back()[h], 0.0, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(G18AndG19, MotionArcPlaneHelix, ::testing::Values(ArcPlane::zx, ArcPlane::yz),
                         [](const ::testing::TestParamInfo<ArcPlane>& i) {
                           return std::string(i.param == ArcPlane::zx ? "G18" : "G19");
                         });

}  // namespace
}  // namespace tnv::fw::motion
