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

double pass_infeed_mm_rev(double overhang_mm, double l1_mm, double s1_mm_rev, double l2_mm, double s2_mm_rev) {
  return fw::infeed_along_overhang_mm_rev(overhang_mm, l1_mm, s1_mm_rev, l2_mm, s2_mm_rev);
}

std::vector<BoringPassSegment> boring_pass_segments(const BoringPassGeometry& g, double s1, double s2) {
  const double l1 = g.overhang_at_top_mm + g.top_depth_mm;
  const double l2 = g.overhang_at_top_mm + g.bottom_depth_mm;
  std::vector<BoringPassSegment> out;
  // The top gauge depth in the first segment, fed at S1 from the approach on.
  double from = std::min(g.top_depth_mm, 0.0) - g.approach_mm;
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
    out.push_back({from, to, pass_infeed_mm_rev(mid_overhang, l1, s1, l2, s2)});
  }
  // The bottom gauge depth in the last segment, fed at S2 (from at least a segment above it).
  out.push_back({std::max(to, g.top_depth_mm), g.bottom_depth_mm + g.overrun_mm, s2});
  return out;
}

std::string mark_feed_per_rev(gcode::GcodeProgram& program, const std::vector<BoringPassSegment>& segments) {
  std::vector<fw::motion::Segment*> feeds;
  for (fw::motion::Segment& s : program.segments)
    if (fw::motion::is_feed_move(s)) feeds.push_back(&s);
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
  const auto nose_z = [&g](double depth_mm) { return g.stock_top_mm - depth_mm + g.tool_length_mm; };
  const double from_depth_mm = std::min(g.top_depth_mm, 0.0) - g.approach_mm;
  std::string text = "G21 G90 G94 G17\n";
  char line[96];
  std::snprintf(line, sizeof line, "G0 Z%.4f\n", nose_z(from_depth_mm));
  text.append(line);
  std::snprintf(line, sizeof line, "S%.1f M3\n", g.spindle_rpm);
  text.append(line);
  std::snprintf(line, sizeof line, "G1 Z%.4f F%.4f\n", nose_z(g.bottom_depth_mm + g.overrun_mm),
                std::max(s1, s2) * g.spindle_rpm);
  text.append(line);
  std::snprintf(line, sizeof line, "G0 Z%.4f\n", nose_z(from_depth_mm));
  text.append(line);
  text.append("M2\n");
  return text;
}

std::string mark_feed_along_depth(gcode::GcodeProgram& program, const BoringPassGeometry& g) {
  std::vector<fw::motion::Segment*> feeds;
  for (fw::motion::Segment& s : program.segments)
    if (fw::motion::is_feed_move(s)) feeds.push_back(&s);
  if (feeds.size() != 1 || feeds[0]->kind != fw::motion::SegmentKind::line)
    return "the pass along the depth is one feed line, the program has " + std::to_string(feeds.size());
  feeds[0]->overhang_at_end_mm = boring_pass_end_overhang_mm(g);
  return "";
}

std::string boring_pass_gcode(const BoringPassGeometry& g, double s1, double s2) {
  const auto nose_z = [&g](double depth_mm) { return g.stock_top_mm - depth_mm + g.tool_length_mm; };
  const std::vector<BoringPassSegment> segments = boring_pass_segments(g, s1, s2);
  std::string text = "G21 G90 G94 G17\n";
  char line[96];
  std::snprintf(line, sizeof line, "G0 Z%.4f\n", nose_z(segments.front().from_depth_mm));
  text.append(line);
  std::snprintf(line, sizeof line, "S%.1f M3\n", g.spindle_rpm);
  text.append(line);
  for (const BoringPassSegment& seg : segments) {
    std::snprintf(line, sizeof line, "G1 Z%.4f F%.4f\n", nose_z(seg.to_depth_mm), seg.infeed_mm_rev * g.spindle_rpm);
    text.append(line);
  }
  std::snprintf(line, sizeof line, "G0 Z%.4f\n", nose_z(segments.front().from_depth_mm));
  text.append(line);
  text.append("M2\n");
  return text;
}

}  // namespace tnv::hil
