// One S4 part as a program: the feed per revolution follows eq. (3)'s
// power law through the planner's two infeeds, exactly S1 and S2 over the
// gauge depths, and the G-code feeds Z at F = S n from above the mouth to
// below the bottom gauge depth.
#include "tools/hil/boring_pass_program.hpp"

#include "firmware/adaptive/boring/infeed_schedule.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace tnv::hil {
namespace {

TEST(BoringPassProgram, ThePowerLawPassesThroughBothInfeeds) {
  EXPECT_NEAR(fw::infeed_along_overhang_mm_rev(40.0, 40.0, 0.25, 310.0, 0.084), 0.25, 1e-15);
  EXPECT_NEAR(fw::infeed_along_overhang_mm_rev(310.0, 40.0, 0.25, 310.0, 0.084), 0.084, 1e-15);
  // Eq. (3) for Table 1's set (C 0.0871, alpha 0.5025, beta 0.2676) at L = 150 mm, from its values at 40 and 310 mm.
  const auto eq3 = [](double l) { return std::pow(0.1165 / (0.0871 * std::pow(l, 0.2676)), 1.0 / 0.5025); };
  EXPECT_NEAR(fw::infeed_along_overhang_mm_rev(150.0, 40.0, eq3(40.0), 310.0, eq3(310.0)), eq3(150.0), 1e-12);
}

TEST(BoringPassProgram, SegmentsCoverThePassWithTheGaugeDepthsAtTheirInfeeds) {
  const BoringPassGeometry g = boring_pass_geometry(emu::Scenario{}, 3000.0);
  const std::vector<BoringPassSegment> seg = boring_pass_segments(g, 0.25, 0.084);
  ASSERT_GE(seg.size(), 3u);
  EXPECT_EQ(seg.front().from_depth_mm, -10.0);
  EXPECT_EQ(seg.back().to_depth_mm, 274.0);
  for (std::size_t i = 1; i < seg.size(); ++i) {
    EXPECT_EQ(seg[i].from_depth_mm, seg[i - 1].to_depth_mm) << "contiguous";
    EXPECT_LE(seg[i].infeed_mm_rev, seg[i - 1].infeed_mm_rev) << "deeper, a smaller infeed";
    if (i + 1 < seg.size()) {
      EXPECT_LE(seg[i].to_depth_mm - seg[i].from_depth_mm, 12.0 + 1e-9) << "between the ends";
    }
  }
  EXPECT_EQ(seg.front().infeed_mm_rev, 0.25);
  EXPECT_GE(seg.front().to_depth_mm, 10.0) << "the top gauge depth well inside the first segment";
  EXPECT_EQ(seg.back().infeed_mm_rev, 0.084);
  EXPECT_LE(seg.back().from_depth_mm, 260.0) << "the bottom gauge depth well inside the last segment";
}

TEST(BoringPassProgram, TheProgramFeedsZAtSTimesN) {
  const BoringPassGeometry g = boring_pass_geometry(emu::Scenario{}, 3000.0);
  const std::string text = boring_pass_gcode(g, 0.25, 0.084);
  std::istringstream lines(text);
  std::vector<std::string> all;
  for (std::string line; std::getline(lines, line);) all.push_back(line);
  // Tool point 10 mm above the stock top (-150) with a 125 mm tool: the nose at -15.
  EXPECT_EQ(all.at(1), "G0 Z-15.0000");
  EXPECT_EQ(all.at(2), "S3000.0 M3");
  EXPECT_EQ(all.at(3).rfind("G1 Z", 0), 0u);
  EXPECT_NE(all.at(3).find("F750.0000"), std::string::npos) << all.at(3) << ": 0.25 mm/rev x 3000 rpm";
  EXPECT_EQ(all.at(all.size() - 3), "G1 Z-299.0000 F252.0000") << "4 mm below the bottom gauge depth, at S2";
  EXPECT_EQ(all.at(all.size() - 2), "G0 Z-15.0000");
  EXPECT_EQ(all.back(), "M2");
}

// On the node every feed line of the pass is a feed per revolution at its segment's infeed.
TEST(BoringPassProgram, EveryFeedLineBecomesAFeedPerRevolutionAtItsSegmentsInfeed) {
  const BoringPassGeometry g = boring_pass_geometry(emu::Scenario{}, 6000.0);
  gcode::GcodeOptions options;
  options.limits.axis[2].position_min_mm = -300.0;
  gcode::GcodeResult parsed = gcode::parse_gcode(boring_pass_gcode(g, 0.25, 0.084), options);
  ASSERT_FALSE(parsed.error);
  const std::vector<BoringPassSegment> seg = boring_pass_segments(g, 0.25, 0.084);
  ASSERT_EQ(mark_feed_per_rev(parsed.program, seg), "");
  std::size_t k = 0;
  for (const fw::motion::Segment& s : parsed.program.segments) {
    if (!fw::motion::is_feed_move(s)) {
      EXPECT_FALSE(s.per_rev()) << "a rapid or the spindle's start stays as it is";
      continue;
    }
    ASSERT_LT(k, seg.size());
    EXPECT_EQ(s.feed_mm_rev, seg[k].infeed_mm_rev);
    EXPECT_NEAR(s.feed_mm_s, seg[k].infeed_mm_rev * 6000.0 / 60.0, 1e-6) << "its speed at the commanded spindle speed (F to 1e-4 mm/min)";
    ++k;
  }
  EXPECT_EQ(k, seg.size());
  // Another pass's segments do not fit this program: refused, nothing changed.
  gcode::GcodeResult other = gcode::parse_gcode(boring_pass_gcode(g, 0.25, 0.084), options);
  ASSERT_FALSE(other.error);
  std::vector<BoringPassSegment> fewer = seg;
  fewer.pop_back();
  EXPECT_NE(mark_feed_per_rev(other.program, fewer), "");
  for (const fw::motion::Segment& s : other.program.segments) EXPECT_FALSE(s.per_rev());
}

// Along the depth: one feed line from 10 mm above the mouth to 4 mm below
// the bottom gauge depth at the larger infeed's F, marked with the bar's
// overhang at its end (the node takes the infeed from its schedule there).
TEST(BoringPassProgram, AlongTheDepthThePassIsOneLineMarkedWithTheOverhangAtItsEnd) {
  const BoringPassGeometry g = boring_pass_geometry(emu::Scenario{}, 6000.0);
  gcode::GcodeOptions options;
  options.limits.axis[2].position_min_mm = -300.0;
  gcode::GcodeResult parsed = gcode::parse_gcode(boring_pass_depth_gcode(g, 0.084, 0.25), options);
  ASSERT_FALSE(parsed.error);
  EXPECT_DOUBLE_EQ(boring_pass_end_overhang_mm(g), 40.0 + 270.0 + 4.0);
  ASSERT_EQ(mark_feed_along_depth(parsed.program, g), "");
  int feeds = 0;
  for (const fw::motion::Segment& s : parsed.program.segments) {
    if (!fw::motion::is_feed_move(s)) {
      EXPECT_FALSE(s.per_rev()) << "a rapid or the spindle's start stays as it is";
      continue;
    }
    ++feeds;
    EXPECT_TRUE(s.per_rev_along_depth());
    EXPECT_EQ(s.overhang_at_end_mm, 314.0);
    EXPECT_EQ(s.feed_mm_rev, 0.0);
    EXPECT_NEAR(s.end_mm[2], g.stock_top_mm - 274.0 + g.tool_length_mm, 1e-9);
    EXPECT_NEAR(s.feed_mm_s, 0.25 * 6000.0 / 60.0, 1e-6) << "the larger infeed's speed: the look-ahead's bound";
  }
  EXPECT_EQ(feeds, 1);
  // The segmented program is not one line: refused, nothing changed.
  gcode::GcodeResult other = gcode::parse_gcode(boring_pass_gcode(g, 0.25, 0.084), options);
  ASSERT_FALSE(other.error);
  EXPECT_NE(mark_feed_along_depth(other.program, g), "");
  for (const fw::motion::Segment& s : other.program.segments) EXPECT_FALSE(s.per_rev());
}

TEST(BoringPassProgram, APassBelowTheTravelIsRefused) {
  BoringPassGeometry g = boring_pass_geometry(emu::Scenario{}, 3000.0);
  EXPECT_EQ(validate_boring_pass(g, -300.0), "");
  g.overrun_mm = 4.0;  // the nose to -299
  EXPECT_EQ(validate_boring_pass(g, -300.0), "");
  g.overrun_mm = 6.0;
  EXPECT_NE(validate_boring_pass(g, -300.0).find("overrun_mm"), std::string::npos);
  g = boring_pass_geometry(emu::Scenario{}, 0.0);
  EXPECT_NE(validate_boring_pass(g, -300.0).find("spindle_rpm"), std::string::npos);
}

}  // namespace
}  // namespace tnv::hil
