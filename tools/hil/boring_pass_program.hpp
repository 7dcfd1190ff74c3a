#pragma once
// One S4 part as a program for the machine (reference plant "Boring (S4,
// on real axes)"): the bar starts above the pre-drilled hole, the spindle
// comes to speed, Z feeds down through the bore to just below the bottom
// gauge depth and rapids back out. The feed per revolution follows the
// planner's two infeeds along the overhang by eq. (3)'s power law
//   S(L) = S1 (L / L1)^(ln(S2 / S1) / ln(L2 / L1))
// (eq. (3) with the planner's estimates is exactly this line in log S,
// log L through its infeeds at L1 and L2: fw::infeed_along_overhang_mm_rev),
// held constant over short segments, and exactly S1 / S2 over the segments
// holding the gauge depths.
// The G-code's feeds are G94 (mm/min) at the commanded spindle speed,
// F = S n: what the node's look-ahead plans with. Cut on the node, every
// feed line is a feed per revolution (mark_feed_per_rev(): SEGMENT kind
// line_per_rev): the node moves Z at S times the spindle speed it measures,
// tick by tick (firmware/motion/spindle_synced_feed.hpp), so a spindle that
// droops or ramps changes the feed, not the infeed. The pass the machine run
// cuts by default is boring_pass_depth_gcode(): one line along which the
// node evaluates S(L) itself every tick, not held over segments.
#include <string>
#include <vector>

#include "emulator/scenario.hpp"
#include "tools/gcode/gcode_program.hpp"

namespace tnv::hil {

struct BoringPassGeometry {
  double stock_top_mm = -150.0;       // z_top: the tool point's Z at the bore's mouth (machine coordinates)
  double tool_length_mm = 125.0;      // spindle nose to tool point: program Z = tool point + this
  double overhang_at_top_mm = 40.0;   // L0
  double top_depth_mm = 0.0;          // the gauge depths below z_top
  double bottom_depth_mm = 270.0;
  double spindle_rpm = 3000.0;        // S ... M3
  double approach_mm = 10.0;          // the feed starts this far above z_top (room to settle at S1 before the mouth)
  double overrun_mm = 4.0;            // and ends this far below the bottom gauge depth (room to brake from 50 mm/s after it)
  double segment_mm = 10.0;           // the feed is held over segments of about this length
};

// The geometry a machine scenario ([stock], [tool], [boring]) describes, at this spindle speed.
BoringPassGeometry boring_pass_geometry(const emu::Scenario& scenario, double spindle_rpm);

// "" if valid, else "field: reason" (a pass needs the top gauge depth above the bottom one,
// positive lengths, a spindle speed, and its deepest point within Z's travel).
std::string validate_boring_pass(const BoringPassGeometry& g, double z_travel_bottom_mm);

// Where every pass starts and goes back to (the approach above the mouth, or above
// the top gauge depth if that is above the mouth) and where its feed ends (the
// overrun below the bottom gauge depth): depths below the stock's top, mm.
double boring_pass_start_depth_mm(const BoringPassGeometry& g);
double boring_pass_end_depth_mm(const BoringPassGeometry& g);

// One feed segment of the pass: from the depth above to the depth below, at this infeed.
struct BoringPassSegment {
  double from_depth_mm = 0.0;  // below z_top (negative: above the mouth)
  double to_depth_mm = 0.0;
  double infeed_mm_rev = 0.0;
};
std::vector<BoringPassSegment> boring_pass_segments(const BoringPassGeometry& g, double infeed_top_mm_rev,
                                                    double infeed_bottom_mm_rev);

// The program of one part (G21 G90 G94; metric, absolute, feed per minute; ends with M2).
std::string boring_pass_gcode(const BoringPassGeometry& g, double infeed_top_mm_rev, double infeed_bottom_mm_rev);

// The parsed program of boring_pass_gcode() with its feed lines per
// revolution: the k-th feed line (not a rapid, not a dwell) gets
// segments[k].infeed_mm_rev as Segment::feed_mm_rev. "" or why not (the
// program's feed lines are not the segments': nothing is changed then).
std::string mark_feed_per_rev(gcode::GcodeProgram& program, const std::vector<BoringPassSegment>& segments);

// The pass as the node cuts it along the depth: one feed line from the
// approach above the mouth to the overrun below the bottom gauge depth,
// at F = max(S1, S2) n (the look-ahead's upper bound; G94, as the G-code
// reader has no G95) and otherwise as boring_pass_gcode().
// mark_feed_along_depth() makes that line a feed per revolution along the
// depth (SEGMENT kind line_per_rev_depth): the node takes its infeed from
// the planner's schedule at the bar's overhang every tick, S4 eq. (3)
// continuously (firmware/adaptive/boring/infeed_schedule.hpp InfeedAlongOverhang).
std::string boring_pass_depth_gcode(const BoringPassGeometry& g, double infeed_top_mm_rev,
                                    double infeed_bottom_mm_rev);
// The bar's overhang where that line ends (L0 + the bottom gauge depth + the overrun).
double boring_pass_end_overhang_mm(const BoringPassGeometry& g);
// "" or why not (the program's feed lines are not the one line: nothing is changed then).
std::string mark_feed_along_depth(gcode::GcodeProgram& program, const BoringPassGeometry& g);

}  // namespace tnv::hil
