#include "firmware/can/segment_wire.hpp"

#include <algorithm>
#include <cmath>

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"

namespace tnv::fw::can {

using namespace fields;
using motion::PlanePoint;
using motion::SegmentKind;

namespace {

struct Chord {
  PlanePoint mid{};
  PlanePoint unit{};  // start -> end
  PlanePoint left{};  // unit rotated by +90 degrees
};

// Host and node call this with the same doubles, so they get the same frame.
// In the plane's two coordinates (first, second): mid, unit and left hold those only.
bool chord_of(const PlanePoint& start_mm, const PlanePoint& end_mm, motion::PlaneAxes p, Chord& c) noexcept {
  const double dx = end_mm[p.first] - start_mm[p.first];
  const double dy = end_mm[p.second] - start_mm[p.second];
  const double length = std::hypot(dx, dy);
  if (!(length >= kMinChordMm)) return false;
  c.mid = {0.5 * (start_mm[p.first] + end_mm[p.first]), 0.5 * (start_mm[p.second] + end_mm[p.second])};
  c.unit = {dx / length, dy / length};
  c.left = {-c.unit[1], c.unit[0]};
  return true;
}

bool is_arc(WireKind k) noexcept {
  return k == WireKind::arc_cw || k == WireKind::arc_ccw || k == WireKind::arc_cw_exact_stop ||
         k == WireKind::arc_ccw_exact_stop;
}

WireKind wire_kind(const motion::Segment& s) noexcept {
  switch (s.kind) {
    case SegmentKind::dwell:
      switch (s.spindle) {
        case motion::SpindleChange::forward: return WireKind::spindle_forward;
        case motion::SpindleChange::reverse: return WireKind::spindle_reverse;
        case motion::SpindleChange::stop: return WireKind::spindle_stop;
        case motion::SpindleChange::none: break;
      }
      return s.pause ? WireKind::pause : WireKind::dwell;
    case SegmentKind::arc_cw: return s.exact_stop ? WireKind::arc_cw_exact_stop : WireKind::arc_cw;
    case SegmentKind::arc_ccw: return s.exact_stop ? WireKind::arc_ccw_exact_stop : WireKind::arc_ccw;
    case SegmentKind::line: break;
  }
  if (s.probe != motion::ProbeKind::none)
    return static_cast<WireKind>(static_cast<std::uint8_t>(WireKind::probe_toward_or_error) +
                                 static_cast<std::uint8_t>(s.probe) - 1);
  if (s.rapid) return s.exact_stop ? WireKind::rapid_exact_stop : WireKind::rapid;
  if (s.per_rev_along_depth())
    return s.exact_stop ? WireKind::line_per_rev_depth_exact_stop : WireKind::line_per_rev_depth;
  if (s.per_rev()) return s.exact_stop ? WireKind::line_per_rev_exact_stop : WireKind::line_per_rev;
  return s.exact_stop ? WireKind::line_exact_stop : WireKind::line;
}

}  // namespace

bool chord_centre(const PlanePoint& start_mm, const PlanePoint& end_mm, const PlanePoint& centre_mm,
                  motion::ArcPlane plane, ChordCentre& out) noexcept {
  const motion::PlaneAxes p = motion::plane_axes(plane);
  Chord c;
  if (!chord_of(start_mm, end_mm, p, c)) return false;
  const double vx = centre_mm[p.first] - c.mid[0];
  const double vy = centre_mm[p.second] - c.mid[1];
  out.normal_mm = vx * c.left[0] + vy * c.left[1];
  out.along_mm = vx * c.unit[0] + vy * c.unit[1];
  return true;
}

bool centre_from_chord(const PlanePoint& start_mm, const PlanePoint& end_mm, const ChordCentre& cc,
                       motion::ArcPlane plane, PlanePoint& centre_mm) noexcept {
  const motion::PlaneAxes p = motion::plane_axes(plane);
  Chord c;
  if (!chord_of(start_mm, end_mm, p, c)) return false;
  const std::size_t axes[2] = {p.first, p.second};
  for (std::size_t i = 0; i < 2; ++i)
    centre_mm[axes[i]] = c.mid[i] + cc.along_mm * c.unit[i] + cc.normal_mm * c.left[i];
  return true;
}

double wire_position_mm(double mm) noexcept {
  // The codec's own rounding and scaling (frame_codec.cpp write() then read()), held to the i24 range.
  const double raw = std::isfinite(mm) ? std::clamp(std::round(mm / kSegmentX.scale), -8388608.0, 8388607.0) : 0.0;
  return static_cast<double>(static_cast<std::int32_t>(raw)) * kSegmentX.scale;
}

const FieldDef* encode_segment(const motion::Segment& s, const PlanePoint& start_mm, std::uint8_t node,
                               std::uint8_t tag, SegmentFrames& out) noexcept {
  out = {};
  out.head = make_frame(kSegmentMsg, node);
  write_raw(out.head, kSegmentTag, tag);
  const WireKind kind = wire_kind(s);
  write_raw(out.head, kSegmentKind, static_cast<std::uint32_t>(kind));
  const bool spindle_start = kind == WireKind::spindle_forward || kind == WireKind::spindle_reverse;
  if (kind == WireKind::dwell || spindle_start || kind == WireKind::pause || kind == WireKind::spindle_stop) {
    // Where the path is, one frame. A dwell's time or a start's speed in x:
    // one that rounds to nothing would be refused by the queue (bad_dwell,
    // bad_spindle).
    if (kind == WireKind::dwell || spindle_start) {
      const double amount = spindle_start ? s.spindle_rpm / kSpindleRpmPerX : s.dwell_s;
      if (!write(out.head, kSegmentX, amount) || read_raw(out.head, kSegmentX) == 0 || read(out.head, kSegmentX) < 0.0)
        return &kSegmentX;
    }
    out.end_mm = start_mm;
    return nullptr;
  }
  if (!write(out.head, kSegmentX, s.end_mm[0])) return &kSegmentX;
  if (!write(out.head, kSegmentY, s.end_mm[1])) return &kSegmentY;
  out.end_mm = start_mm;  // axes the wire does not carry stay
  out.end_mm[0] = read(out.head, kSegmentX);
  out.end_mm[1] = read(out.head, kSegmentY);
  const bool other_plane = s.kind != SegmentKind::line && s.plane != motion::ArcPlane::xy;
  if (other_plane) {
    if (static_cast<std::uint8_t>(s.plane) >= motion::kArcPlaneCount) return &kPlaneField;
    out.z = make_frame(kSegmentPlaneMsg, node);
    write_raw(out.z, kPlaneTag, tag);
    write_raw(out.z, kPlaneField, static_cast<std::uint32_t>(s.plane));
    if (!write(out.z, kPlaneZ, s.end_mm[kProgramZ])) return &kPlaneZ;
    out.has_z = true;
    out.end_mm[kProgramZ] = read(out.z, kPlaneZ);
  } else {
    out.z = make_frame(kSegmentZMsg, node);
    write_raw(out.z, kSegmentZTag, tag);
    if (!write(out.z, kSegmentZField, s.end_mm[kProgramZ])) return &kSegmentZField;
    out.has_z = read(out.z, kSegmentZField) != start_mm[kProgramZ];
    if (out.has_z) out.end_mm[kProgramZ] = read(out.z, kSegmentZField);
    else out.z = {};
  }
  out.tail = make_frame(kSegmentTailMsg, node);
  out.has_tail = true;
  write_raw(out.tail, kTailTag, tag);
  if (!write(out.tail, kTailFeed, s.feed_mm_s) || read_raw(out.tail, kTailFeed) == 0) return &kTailFeed;
  if (s.per_rev()) {
    // Only a plain feed line is carried per revolution (the queue refuses the rest as bad_kind).
    if (!is_per_rev_kind(kind)) return &kSegmentKind;
    if (s.per_rev_along_depth()) {
      if (!write(out.tail, kTailCentreNormal, s.overhang_at_end_mm) || !(read(out.tail, kTailCentreNormal) > 0.0))
        return &kTailCentreNormal;
      return nullptr;
    }
    if (!write(out.tail, kTailCentreNormal, s.feed_mm_rev / kFeedRevPerNormal) ||
        read_raw(out.tail, kTailCentreNormal) == 0 || read(out.tail, kTailCentreNormal) < 0.0)
      return &kTailCentreNormal;
    return nullptr;
  }
  if (s.kind == SegmentKind::line) return nullptr;
  ChordCentre cc;
  if (!chord_centre(start_mm, out.end_mm, s.centre_mm, s.plane, cc)) return &kTailCentreNormal;
  if (!write(out.tail, kTailCentreNormal, cc.normal_mm)) return &kTailCentreNormal;
  if (!write(out.tail, kTailCentreAlong, cc.along_mm)) return &kTailCentreAlong;
  return nullptr;
}

const FieldDef* encode_tool_change(int tool, const PlanePoint& at_mm, std::uint8_t node, std::uint8_t tag,
                                   SegmentFrames& out) noexcept {
  out = {};
  out.head = make_frame(kSegmentMsg, node);
  write_raw(out.head, kSegmentTag, tag);
  write_raw(out.head, kSegmentKind, static_cast<std::uint32_t>(WireKind::tool_change));
  if (tool < 0 || !write(out.head, kSegmentX, static_cast<double>(tool) / kToolPerX)) return &kSegmentX;
  out.end_mm = at_mm;
  return nullptr;
}

bool decode_head(const hal::CanFrame& head, SegmentHead& out) noexcept {
  const std::uint32_t kind = read_raw(head, kSegmentKind);
  if (kind >= kWireKindCount) return false;
  out.kind = static_cast<WireKind>(kind);
  out.end_mm = {read(head, kSegmentX), read(head, kSegmentY)};
  out.dwell_s = read(head, kSegmentX);
  out.spindle_rpm = read(head, kSegmentX) * kSpindleRpmPerX;
  out.tool = static_cast<std::int32_t>(std::lround(read(head, kSegmentX) * kToolPerX));
  return true;
}

bool decode_z(const hal::CanFrame& z, SegmentHead& head) noexcept {
  if (!wire_kind_has_tail(head.kind) || head.has_z) return false;
  head.has_z = true;
  head.end_z_mm = read(z, kSegmentZField);
  return true;
}

ErrorCode decode_plane(const hal::CanFrame& frame, SegmentHead& head) noexcept {
  if (!wire_kind_has_tail(head.kind) || head.has_z) return ErrorCode::not_ready;
  const std::uint32_t plane = read_raw(frame, kPlaneField);
  if (!is_arc(head.kind) || plane >= motion::kArcPlaneCount) return ErrorCode::out_of_range;
  head.has_z = true;
  head.end_z_mm = read(frame, kPlaneZ);
  head.plane = static_cast<motion::ArcPlane>(plane);
  return ErrorCode::ok;
}

bool decode_segment(const SegmentHead& head, const hal::CanFrame* tail, const PlanePoint& start_mm,
                    motion::Segment& out) noexcept {
  switch (head.kind) {
    case WireKind::pause:
    case WireKind::tool_change: out = motion::pause_here(); return true;
    case WireKind::spindle_forward: out = motion::spindle_here(motion::SpindleChange::forward, head.spindle_rpm); return true;
    case WireKind::spindle_reverse: out = motion::spindle_here(motion::SpindleChange::reverse, head.spindle_rpm); return true;
    case WireKind::spindle_stop: out = motion::spindle_here(motion::SpindleChange::stop, 0.0); return true;
    default: break;
  }
  if (head.kind == WireKind::dwell || tail == nullptr) {
    out = motion::dwell_for(head.dwell_s);
    return head.kind == WireKind::dwell;
  }
  const double feed_mm_s = read(*tail, kTailFeed);
  const bool exact_stop = head.kind == WireKind::line_exact_stop || head.kind == WireKind::arc_cw_exact_stop ||
                          head.kind == WireKind::arc_ccw_exact_stop || head.kind == WireKind::rapid_exact_stop;
  const bool rapid = head.kind == WireKind::rapid || head.kind == WireKind::rapid_exact_stop;
  PlanePoint end_mm = start_mm;  // axes the wire does not carry stay
  end_mm[0] = head.end_mm[0];
  end_mm[1] = head.end_mm[1];
  if (head.has_z) end_mm[kProgramZ] = head.end_z_mm;
  if (is_probe_kind(head.kind)) {
    const auto kind = static_cast<motion::ProbeKind>(static_cast<std::uint8_t>(head.kind) -
                                                     static_cast<std::uint8_t>(WireKind::probe_toward_or_error) + 1);
    out = motion::probe_to(kind, end_mm, feed_mm_s);
    return true;
  }
  if (is_per_rev_kind(head.kind)) {
    out = motion::line_to(end_mm, feed_mm_s);
    if (is_per_rev_depth_kind(head.kind))
      out.overhang_at_end_mm = read(*tail, kTailCentreNormal);
    else
      out.feed_mm_rev = read(*tail, kTailCentreNormal) * kFeedRevPerNormal;
    out.exact_stop = head.kind == WireKind::line_per_rev_exact_stop || head.kind == WireKind::line_per_rev_depth_exact_stop;
    return true;
  }
  if (head.kind == WireKind::line || head.kind == WireKind::line_exact_stop || rapid) {
    out = motion::line_to(end_mm, feed_mm_s);
    out.rapid = rapid;
  } else {
    const ChordCentre cc{read(*tail, kTailCentreNormal), read(*tail, kTailCentreAlong)};
    PlanePoint centre_mm = start_mm;  // the plane's two coordinates from the chord
    if (!centre_from_chord(start_mm, end_mm, cc, head.plane, centre_mm)) return false;
    const bool clockwise = head.kind == WireKind::arc_cw || head.kind == WireKind::arc_cw_exact_stop;
    out = motion::arc_to(clockwise, end_mm, centre_mm, feed_mm_s, 0, head.plane);
  }
  out.exact_stop = exact_stop;
  return true;
}

}  // namespace tnv::fw::can
