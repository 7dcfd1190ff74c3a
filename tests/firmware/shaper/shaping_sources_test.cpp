// The reference sources the shaper is fed with in the tick: the S-curve
// point-to-point move and the operator jog stream with its dead man.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "firmware/trajectory/jog_limits.hpp"
#include "firmware/trajectory/point_to_point_move.hpp"
#include "tests/firmware/test_units.hpp"

namespace tnv::fw {
namespace {

using test_units::kPeriodS;

TEST(PointToPointMove, SCurveWithTheStatedMoveTime) {
  const MoveSpec spec{hal::Axis::y, -12.0, 60.0, 0.05, 0.0};
  ASSERT_STREQ(validate(spec), "");
  const PointToPointMove move(spec, 3.0);
  EXPECT_NEAR(move.duration_s(), 12.0 / 60.0 + 0.05, 1e-15) << "move time (s)";
  EXPECT_EQ(move.at(0.0).position_mm, 3.0);
  EXPECT_EQ(move.at(0.0).speed_mm_s, 0.0);
  EXPECT_EQ(move.at(move.duration_s()).position_mm, -9.0) << "end point exact";
  EXPECT_EQ(move.at(10.0).speed_mm_s, 0.0);
  EXPECT_NEAR(move.at(0.1).speed_mm_s, -60.0, 1e-12) << "cruise";
  // Raised-cosine ramp: speed and acceleration continuous, peak acceleration F pi / (2 T_r).
  double peak_accel = 0.0;
  for (double t = 0.0; t < move.duration_s(); t += 1e-4)
    peak_accel = std::fmax(peak_accel, std::fabs(move.at(t + 1e-4).speed_mm_s - move.at(t).speed_mm_s) / 1e-4);
  EXPECT_NEAR(peak_accel, 60.0 * std::numbers::pi / (2.0 * 0.05), 5.0) << "mm/s^2";
}

TEST(PointToPointMove, ValidationNamesTheField) {
  EXPECT_STREQ(validate(MoveSpec{hal::Axis::x, NAN, 50.0, 0.02, 0.0}), "distance_mm must be finite and non-zero");
  EXPECT_STREQ(validate(MoveSpec{hal::Axis::x, 5.0, 50.0, -0.1, 0.0}), "ramp_s must be >= 0 and finite");
  EXPECT_STREQ(validate(MoveSpec{hal::Axis::x, 5.0, 50.0, 0.02, INFINITY}), "dwell_s must be >= 0 and finite");
  EXPECT_NE(std::string(validate(MoveSpec{hal::Axis::x, 0.5, 50.0, 0.02, 0.0})).find("ramps do not fit"),
            std::string::npos);
}

TEST(JogLimits, ValidationNamesTheField) {
  EXPECT_TRUE(validate(JogLimits{50.0, 1000.0, 0.1}).ok);
  EXPECT_FALSE(validate(JogLimits{50.0, 0.0, 0.1}).ok);
  EXPECT_STREQ(validate(JogLimits{NAN, 1000.0, 0.1}).field, "speed_max_mm_s");
  EXPECT_STREQ(validate(JogLimits{50.0, 1000.0, -1.0}).field, "deadman_s");
}

}  // namespace
}  // namespace tnv::fw
