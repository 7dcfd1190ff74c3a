#include "firmware/trajectory/circle_trajectory.hpp"

#include <gtest/gtest.h>

namespace tnv::fw {
namespace {

TEST(FeedProfile, RaisedCosineRampsCoverHalfTheirLengthAtFeed) {
  const FeedProfile p(37.69911184, 2.0, 0.1);
  EXPECT_NEAR(p.duration_s(), 37.69911184 / 2.0 + 0.1, 1e-12);
  EXPECT_NEAR(p.at(0.1).distance_mm, 0.1, 1e-12);  // F * Tr / 2
  EXPECT_NEAR(p.at(0.05).speed_mm_s, 1.0, 1e-12);
  EXPECT_NEAR(p.at(p.duration_s()).distance_mm, 37.69911184, 1e-9);
  EXPECT_EQ(p.at(p.duration_s() + 1.0).speed_mm_s, 0.0);
}

TEST(FeedProfile, DistanceIsTheIntegralOfSpeedAndBothAreContinuous) {
  const FeedProfile p(10.0, 2.0, 0.1);
  const double dt = 1e-5;
  double integral = 0.0;
  double last_speed = 0.0, last_distance = 0.0;
  for (double t = 0.0; t < p.duration_s() + 0.01; t += dt) {
    const PathPoint a = p.at(t);
    const PathPoint b = p.at(t + dt);
    integral += 0.5 * (a.speed_mm_s + b.speed_mm_s) * dt;
    EXPECT_LT(std::fabs(b.speed_mm_s - a.speed_mm_s), 2.0 * 3.1416 / 0.2 * dt * 1.01) << "speed jump at t=" << t;
    last_speed = b.speed_mm_s;
    last_distance = b.distance_mm;
  }
  EXPECT_NEAR(integral, last_distance, 1e-6);
  EXPECT_EQ(last_speed, 0.0);
}

TEST(CircleTrajectory, StartsAtRZeroRunsCounterClockwiseAndCloses) {
  const CircleTrajectory c(CircleSpec{});
  const PlaneSample s0 = c.at(0.0);
  EXPECT_DOUBLE_EQ(s0.axis[0].position_mm, 6.0);
  EXPECT_DOUBLE_EQ(s0.axis[1].position_mm, 0.0);
  const PlaneSample quarter = c.at(0.05 + 0.25 * 2.0 * 3.14159265358979 * 6.0 / 2.0);
  EXPECT_NEAR(quarter.axis[0].position_mm, 0.0, 1e-9);
  EXPECT_NEAR(quarter.axis[1].position_mm, 6.0, 1e-9);
  EXPECT_NEAR(quarter.axis[0].speed_mm_s, -2.0, 1e-9);  // moving toward -x at the top
  const PlaneSample end = c.at(c.duration_s());
  EXPECT_NEAR(end.axis[0].position_mm, 6.0, 1e-9);
  EXPECT_NEAR(end.axis[1].position_mm, 0.0, 1e-9);
  EXPECT_NEAR(c.duration_s(), 2.0 * 3.14159265358979 * 6.0 / 2.0 + 0.1, 1e-9);
}

TEST(CircleTrajectory, ValidationNamesTheProblem) {
  EXPECT_STREQ(validate(CircleSpec{}), "");
  EXPECT_NE(std::string(validate(CircleSpec{.radius_mm = -1.0})).find("radius_mm"), std::string::npos);
  EXPECT_NE(std::string(validate(CircleSpec{.feed_mm_s = std::nan("")})).find("feed_mm_s"), std::string::npos);
  EXPECT_NE(std::string(validate(CircleSpec{.ramp_s = 100.0})).find("ramp"), std::string::npos);
  EXPECT_NE(std::string(validate(CircleSpec{.dwell_s = -0.1})).find("dwell_s"), std::string::npos);
}

}  // namespace
}  // namespace tnv::fw
