#include "tools/gcode/path_distance.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tools/gcode/gcode_program.hpp"

namespace tnv::gcode {
namespace {

TEST(PathDistance, NearestPointOfLinesAndArcsNotARadius) {
  // Line (0,0)-(10,0), then a ccw quarter arc about (10,10) to (20,10).
  const GcodeResult r = parse_gcode("G1 X10 Y0 F600\nG3 X20 Y10 I0 J10\n");
  ASSERT_FALSE(r.error.has_value());
  const ProgrammedPath path(r.program.geometry);
  EXPECT_NEAR(path.distance_mm({5.0, 0.3}), 0.3, 1e-12);
  EXPECT_NEAR(path.distance_mm({-3.0, 4.0}), 5.0, 1e-12) << "beyond the line's start: distance to its end point";
  // On the arc's sweep: radial distance.
  EXPECT_NEAR(path.distance_mm({10.0 + 11.0 * std::sqrt(0.5), 10.0 - 11.0 * std::sqrt(0.5)}), 1.0, 1e-12);
  // On the arc's circle but outside the swept quarter: the nearest point is
  // on the line (10 mm away); a radius test would say 0.
  EXPECT_NEAR(path.distance_mm({0.0, 10.0}), 10.0, 1e-12);
}

}  // namespace
}  // namespace tnv::gcode
