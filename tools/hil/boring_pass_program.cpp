#include "tools/hil/boring_pass_program.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "firmware/adaptive/boring/infeed_schedule.hpp"

namespace tnv::hil {

BoringPassGeometry boring_pass_geometry(const emu::Scenario& s, double spindle_rpm) {
  BoringPassGeometry g;
  g.stock_top_mm = s.stock.top_mm;
  g.tool_length_mm = s.tool.length_mm;
  g.overhang_at_top_mm = s.boring.overhang_at_top_mm;
  g.top_depth_mm = s.boring.gauge_top_depth_mm;
  g.bottom_depth_mm = s.boring.gauge_bottom_depth_mm;
  g.spindle_rpm = spindle_rpm;
  return g;
}

std::string validate_boring_pass(const BoringPassGeometry& g, double z_travel_bottom_mm) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(g.spindle_rpm)) return "spindle_rpm: must be > 0 and finite";
  if (!positive(g.approach_mm)) return "approach_mm: must be > 0 and finite";
  if (!positive(g.overrun_mm)) return "overrun_mm: must be > 0 and finite";
  if (!positive(g.segment_mm)) return "segment_mm: must be > 0 and finite";
  if (!positive(g.overhang_at_top_mm)) return "overhang_at_top_mm: must be > 0 and finite";
  if (!(std::isfinite(g.top_depth_mm) && std::isfinite(g.bottom_depth_mm) && g.top_depth_mm >= 0.0 &&
        g.top_depth_mm < g.bottom_depth_mm))
    return "bottom_depth_mm: the gauge depths must satisfy 0 <= top < bottom";
  const double deepest_nose_mm = g.stock_top_mm - g.bottom_depth_mm - g.overrun_mm + g.tool_length_mm;
  if (deepest_nose_mm < z_travel_bottom_mm) {
    char text[160];
    std::snprintf(text, sizeof text, "overrun_mm: the pass ends at Z %.3f mm, below the travel's end %.3f mm",
                  deepest_nose_mm, z_travel_bottom_mm);
    return text;
  }
  return "";
}

double boring_pass_start_depth_mm(const BoringPassGeometry& g) { return std::min(g.top_depth_mm, 0.0) - g.approach_mm; }

double boring_pass_end_depth_mm(const BoringPassGeometry& g) { return g.bottom_depth_mm + g.overrun_mm; }

std::vector<BoringPassSegment> boring_pass_segments(const BoringPassGeometry& g, double s1, double s2) {
  const double l1 = g.overhang_at_top_mm + g.top_depth_mm;
  const double l2 = g.overhang_at_top_mm + g.bottom_depth_mm;
  std::vector<BoringPassSegment> out;
  // The top gauge depth in the first segment, fed at S1 from the approach on.
  double from = boring_pass_start_depth_mm(g);
  double to = g.top_depth_mm + g.segment_mm;
  out.push_back({from, to, s1});
  // Between: even segments at the law's infeed at their middle, the last one ending a segment above the bottom depth.
  const double last_start = g.bottom_depth_mm - g.segment_mm;
  const int n = std::max(0, static_cast<int>(std::ceil((last_start - to) / g.segment_mm)));
  const double step = n > 0 ? (last_start - to) / n : 0.0;
  for (int i = 0; i < n; ++i) {
    from = to;
    to = i + 1 == n ? last_start : from + step;
    const double mid_overhang = g.overhang_at_top_mm + 0.5 * (from + to);
    out.push_back({from, to, fw::infeed_along_overhang_mm_rev(mid_overhang, l1, s1, l2, s2)});
  }
  // The bottom gauge depth in the last segment, fed at S2 (from at least a segment above it).
  out.push_back({std::max(to, g.top_depth_mm), boring_pass_end_depth_mm(g), s2});
  return out;
}

namespace {

// The program's feed lines (not its rapids or dwells), in order.
std::vector<fw::motion::Segment*> feed_moves(gcode::GcodeProgram& program) {
  std::vector<fw::motion::Segment*> feeds;
  for (fw::motion::Segment& s : program.segments)
    if (fw::motion::is_feed_move(s)) feeds.push_back(&s);
  return feeds;
}

struct PassFeed {
  double to_depth_mm;
  double feed_mm_min;
};

// The pass's program: down at rapid to the start, the spindle on, the feed
// lines, back up at rapid to the start, M2.
std::string pass_gcode(const BoringPassGeometry& g, const std::vector<PassFeed>& feeds) {
  const auto nose_z = [&g](double depth_mm) { return g.stock_top_mm - depth_mm + g.tool_length_mm; };
  std::string text = "G21 G90 G94 G17\n";
  char line[96];
  std::snprintf(line, sizeof line, "G0 Z%.4f\n", nose_z(boring_pass_start_depth_mm(g)));
  text.append(line);
  std::snprintf(line, sizeof line, "S%.1f M3\n", g.spindle_rpm);
  text.append(line);
  for (const PassFeed& f : feeds) {
    std::snprintf(line, sizeof line, "G1 Z%.4f F%.4f\n", nose_z(f.to_depth_mm), f.feed_mm_min);
    text.append(line);
  }
  std::snprintf(line, sizeof line, "G0 Z%.4f\n", nose_z(boring_pass_start_depth_mm(g)));
  text.append(line);
  text.append("M2\n");
  return text;
}

}  // namespace

std::string mark_feed_per_rev(gcode::GcodeProgram& program, const std::vector<BoringPassSegment>& segments) {
  const std::vector<fw::motion::Segment*> feeds = feed_moves(program);
  if (feeds.size() != segments.size())
    return "the program has " + std::to_string(feeds.size()) + " feed lines, the pass " +
           std::to_string(segments.size()) + " segments";
  for (std::size_t k = 0; k < feeds.size(); ++k)
    if (feeds[k]->kind != fw::motion::SegmentKind::line || !(segments[k].infeed_mm_rev > 0.0))
      return "feed line " + std::to_string(k + 1) + " cannot be fed per revolution";
  for (std::size_t k = 0; k < feeds.size(); ++k) feeds[k]->feed_mm_rev = segments[k].infeed_mm_rev;
  return "";
}

double boring_pass_end_overhang_mm(const BoringPassGeometry& g) {
  return g.overhang_at_top_mm + g.bottom_depth_mm + g.overrun_mm;
}

std::string boring_pass_depth_gcode(const BoringPassGeometry& g, double s1, double s2) {
  return pass_gcode(g, {{boring_pass_end_depth_mm(g), std::max(s1, s2) * g.spindle_rpm}});
}

std::string mark_feed_along_depth(gcode::GcodeProgram& program, const BoringPassGeometry& g) {
  const std::vector<fw::motion::Segment*> feeds = feed_moves(program);
  if (feeds.size() != 1 || feeds[0]->kind != fw::motion::SegmentKind::line)
    return "the pass along the depth is one feed line, the program has " + std::to_string(feeds.size());
  feeds[0]->overhang_at_end_mm = boring_pass_end_overhang_mm(g);
  return "";
}

std::string boring_pass_gcode(const BoringPassGeometry& g, double s1, double s2) {
  std::vector<PassFeed> feeds;
  for (const BoringPassSegment& seg : boring_pass_segments(g, s1, s2))
    feeds.push_back({seg.to_depth_mm, seg.infeed_mm_rev * g.spindle_rpm});
  return pass_gcode(g, feeds);
}

}  // namespace tnv::hil
