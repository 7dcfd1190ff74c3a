// The repository's test pieces through the firmware's motion core at several
// feeds: commanded acceleration and jerk per axis (finite differences of the
// 1 ms reference, as in tests/firmware/motion/motion_run.hpp), the planner's
// deviation from the programmed geometry, and the feed ratio.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "tests/firmware/motion/motion_run.hpp"
#include "tests/sanitized_build.hpp"
#include "tests/tools/gcode/test_piece_path.hpp"
#include "tools/gcode/gcode_program.hpp"
#include "tools/gcode/path_distance.hpp"

namespace tnv::gcode {
namespace {

using test::test_piece_path;

using fw::motion::MotionInterpolator;
using fw::motion::Segment;
using fw::motion::SegmentKind;

struct PieceResult {
  double accel_ratio_max = 0.0;
  double jerk_ratio_max = 0.0;
  double path_deviation_max_um = 0.0;
  double feed_ratio = 0.0;
  double cycle_time_s = 0.0;
};

GcodeProgram load(const char* name) {
  const GcodeResult r = parse_gcode_file(test_piece_path(name));
  EXPECT_FALSE(r.error.has_value()) << name;
  return r.program;
}

// feed_mm_s > 0 replaces every line and arc feed (rapids included).
PieceResult run_piece(const GcodeProgram& program, double feed_mm_s) {
  std::vector<Segment> segments = program.segments;
  GcodeProgram timed = program;
  if (feed_mm_s > 0.0) {
    for (Segment& s : segments)
      if (s.kind != SegmentKind::dwell) s.feed_mm_s = feed_mm_s;
    timed.segments = segments;
  }
  MotionInterpolator m;
  EXPECT_STREQ(m.configure({}, {0.0, 0.0}), "");
  const fw::motion::test::MotionRun run = fw::motion::test::run_program(m, segments);
  EXPECT_EQ(m.stats().underruns, 0u);
  EXPECT_EQ(m.stats().follower.guard_failures, 0u);
  EXPECT_EQ(m.stats().follower.brake_shortfalls, 0u);
  PieceResult r;
  r.accel_ratio_max = run.accel_ratio_max;
  r.jerk_ratio_max = run.jerk_ratio_max;
  const ProgrammedPath path(program.geometry);
  for (const PlanePoint& p : run.position_mm) r.path_deviation_max_um = std::max(r.path_deviation_max_um, path.distance_mm(p) * 1e3);
  r.cycle_time_s = static_cast<double>(run.motion_ticks) * 1e-3;
  r.feed_ratio = timed.programmed_time_s() / r.cycle_time_s;
  return r;
}

void expect_piece(const char* name, double feed_mm_s, double min_feed_ratio = 0.0) {
  const PieceResult r = run_piece(load(name), feed_mm_s);
  std::printf("[motion] %-36s F %5.1f mm/s: accel_ratio_max %.6f jerk_ratio_max %.6f path_deviation_max %.3f um "
              "feed_ratio %.3f cycle %.3f s\n",
              name, feed_mm_s, r.accel_ratio_max, r.jerk_ratio_max, r.path_deviation_max_um, r.feed_ratio,
              r.cycle_time_s);
  EXPECT_LE(r.accel_ratio_max, 1.0 + 1e-6) << name << " at " << feed_mm_s << " mm/s";
  EXPECT_LE(r.jerk_ratio_max, 1.0 + 1e-6) << name << " at " << feed_mm_s << " mm/s";
  EXPECT_LE(r.path_deviation_max_um, fw::motion::MotionLimits{}.path_tolerance_mm * 1e3)
      << name << " at " << feed_mm_s << " mm/s: the reference leaves the programmed path";
  EXPECT_GE(r.feed_ratio, min_feed_ratio) << name << " at " << feed_mm_s << " mm/s";
}

TEST(TestPieceMotion, ChordCircleAtTwentyMillimetresPerSecondKeepsNinetyPercentOfTheFeed) {
  expect_piece("circle_chords_0p1mm.ngc", 0.0, 0.9);  // as programmed: F1200 = 20 mm/s
}

TEST(TestPieceMotion, EveryTestPieceKeepsTheLimitsAndThePathAtEveryFeed) {
  for (const char* name : {"nas979_diamond_circle_square.ngc", "corners_90deg.ngc", "circle_chords_0p1mm.ngc",
                           "spiral.ngc"}) {
    // Each run is judged alone: a sanitizer build leaves out the longest ones (2 and 20 mm/s).
    for (double feed : {2.0, 10.0, 20.0, 50.0})
      if (!tnv::test::kSanitizedBuild || feed == 10.0 || feed == 50.0) expect_piece(name, feed);
  }
}

TEST(TestPieceMotion, AsProgrammedPiecesKeepTheLimits) {
  for (const char* name : {"nas979_diamond_circle_square.ngc", "corners_90deg.ngc", "spiral.ngc"}) expect_piece(name, 0.0);
}

}  // namespace
}  // namespace tnv::gcode
