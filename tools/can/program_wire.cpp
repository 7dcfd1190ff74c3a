#include "tools/can/program_wire.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "firmware/can/node_fields.hpp"

namespace tnv::can_host {

namespace {

using fw::motion::PlanePoint;
using fw::motion::Segment;
using fw::motion::SegmentGeometry;
using fw::motion::SegmentKind;

// Longest dwell one SEGMENT carries (i24 at 0.1 ms is 838.8 s).
constexpr double kMaxWireDwellS = 800.0;
// Halving an arc more than this often means a value no split can fix.
constexpr int kMaxArcSplits = 4;

struct Builder {
  std::uint8_t node = 1;
  WireProgram out{};
  PlanePoint at_mm{};  // where the node's queue ends
  std::string error;

  bool add(const Segment& s, int line, double length_mm) {
    WireElement e;
    if (const fw::can::FieldDef* f = fw::can::encode_segment(s, at_mm, node, 0, e.frames); f != nullptr) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "line %d: %s does not fit the wire (%s.%s)", line, describe(s).c_str(),
                    f == &fw::can::fields::kTailFeed || f == &fw::can::fields::kTailCentreNormal ||
                            f == &fw::can::fields::kTailCentreAlong
                        ? "SEGMENT_TAIL"
                    : f == &fw::can::fields::kSegmentZField ? "SEGMENT_Z"
                    : f == &fw::can::fields::kPlaneField || f == &fw::can::fields::kPlaneZ ? "SEGMENT_PLANE"
                                                                                             : "SEGMENT",
                    f->name);
      error = buf;
      return false;
    }
    e.segment = s;
    if (s.kind != SegmentKind::dwell) e.segment.end_mm = e.frames.end_mm;
    e.line = line;
    e.length_mm = length_mm;
    at_mm = e.frames.end_mm;
    out.length_mm += length_mm;
    out.elements.push_back(e);
    return true;
  }

  // A manual tool change (M6): a pause that tells the node its tool (SEGMENT kind tool_change).
  bool add_tool_change(const Segment& s, int tool, int line) {
    WireElement e;
    if (fw::can::encode_tool_change(tool, at_mm, node, 0, e.frames) != nullptr) {
      error = "line " + std::to_string(line) + ": tool " + std::to_string(tool) +
              " does not fit the wire (SEGMENT.x: tools 0 to 8388607)";
      return false;
    }
    e.segment = s;
    e.line = line;
    out.elements.push_back(e);
    return true;
  }

  static std::string describe(const Segment& s) {
    char buf[120];
    if (s.kind == SegmentKind::dwell) std::snprintf(buf, sizeof buf, "a dwell of %g s", s.dwell_s);
    else
      std::snprintf(buf, sizeof buf, "a move to (%g, %g, %g) mm at %g mm/s", s.end_mm[0], s.end_mm[1],
                    s.end_mm[fw::can::kProgramZ], s.feed_mm_s);
    return buf;
  }

  bool add_arc(const Segment& s, const SegmentGeometry& g, double t0, double t1, int line, int depth) {
    Segment part = s;
    part.end_mm = t1 >= 1.0 ? s.end_mm : g.arc_point(t1);
    part.exact_stop = t1 >= 1.0 && s.exact_stop;
    const double length_mm = g.length_mm * (t1 - t0);
    WireElement probe;
    const fw::can::FieldDef* f = fw::can::encode_segment(part, at_mm, node, 0, probe.frames);
    const bool centre = f == &fw::can::fields::kTailCentreNormal || f == &fw::can::fields::kTailCentreAlong;
    if (!centre || depth >= kMaxArcSplits) return add(part, line, length_mm);
    const double mid = 0.5 * (t0 + t1);
    return add_arc(s, g, t0, mid, line, depth + 1) && add_arc(s, g, mid, t1, line, depth + 1);
  }
};

}  // namespace

bool wire_append(const gcode::GcodeProgram& program, std::size_t from, PlanePoint& at_mm, std::uint8_t node,
                 WireProgram& out, std::string& error) {
  Builder b;
  b.node = node;
  b.at_mm = at_mm;
  b.out = std::move(out);
  bool ok = true;
  for (std::size_t k = from; ok && k < program.segments.size(); ++k) {
    const Segment& s = program.segments[k];
    const SegmentGeometry& g = program.geometry[k];
    const int line = static_cast<int>(s.tag);
    if (fw::motion::is_program_action(s)) {
      const auto p = std::ranges::find(program.pauses, k, &gcode::ProgramPause::segment);
      const bool tool_change = p != program.pauses.end() && p->reason == gcode::PauseReason::tool_change;
      ok = tool_change ? b.add_tool_change(s, p->tool, line) : b.add(s, line, 0.0);
      if (ok && p != program.pauses.end()) b.out.elements.back().pause = *p;
    } else if (s.kind == SegmentKind::dwell) {
      for (double left_s = s.dwell_s; ok && left_s > 0.0; left_s -= kMaxWireDwellS)
        ok = b.add(fw::motion::dwell_for(std::min(left_s, kMaxWireDwellS), s.tag), line, 0.0);
    } else if (s.kind == SegmentKind::line) {
      ok = b.add(s, line, g.length_mm);
    } else {
      ok = b.add_arc(s, g, 0.0, 1.0, line, 0);
    }
  }
  out = std::move(b.out);
  if (!ok) {
    error = b.error;
    return false;
  }
  at_mm = b.at_mm;
  return true;
}

std::optional<WireProgram> wire_program(const gcode::GcodeProgram& program, const PlanePoint& start_mm,
                                        std::uint8_t node, std::string& error) {
  WireProgram out;
  PlanePoint at_mm = start_mm;
  if (!wire_append(program, 0, at_mm, node, out, error)) return std::nullopt;
  return out;
}

double length_fraction(const WireProgram& program, std::size_t elements_done) {
  if (program.length_mm <= 0.0) return program.elements.empty() ? 1.0 : double(elements_done) / double(program.elements.size());
  double done_mm = 0.0;
  for (std::size_t k = 0; k < elements_done && k < program.elements.size(); ++k) done_mm += program.elements[k].length_mm;
  return done_mm / program.length_mm;
}

}  // namespace tnv::can_host
