#pragma once
// A program element (motion/segment.hpp) on the wire: SEGMENT carries the
// kind and the end point (a dwell's time), SEGMENT_TAIL the feed and an
// arc's centre (protocol_messages.hpp). Shared by the node (decode) and
// the host (encode), so both quantise the same way.
//
// Positions are i24 at 0.1 um (+-838 mm). An arc's centre travels in chord
// coordinates: its offset from the midpoint of start -> end along the
// chord's left normal (i24) and along the chord (i16, +-3.2767 mm). Both
// sides compute the chord from the same doubles (the node's queue end is
// the previous element's decoded end point), so the node rebuilds the
// centre to 0.1 um. A full circle has no chord, and a centre far off the
// chord's bisector does not fit: the host sends such arcs in two halves.
// Why not x and y of the centre: two frames hold 14 payload bytes after
// the tags, and end (6) + centre (6) + feed (2) + kind (1) is 15.
//
// Z's end point rides in a third frame, SEGMENT_Z, between the SEGMENT
// and its SEGMENT_TAIL, sent only when the element moves Z (a plunge, a
// retract, a helix): XY elements keep their two frames (bus load), and
// an element without it keeps Z where it starts.
//
// An arc in the ZX (G18) or YZ (G19) plane sends SEGMENT_PLANE in
// SEGMENT_Z's place: its plane and Z's end point (always). Its centre
// travels in the chord frame of that plane (the chord of the start and end
// points' two coordinates in it, first axis then second), so the tail is
// the same two numbers. XY elements are unchanged.
#include <cstdint>

#include "firmware/can/protocol_messages.hpp"
#include "firmware/motion/segment.hpp"
#include "hal/can_port.hpp"

namespace tnv::fw::can {

// SEGMENT.kind
enum class WireKind : std::uint8_t {
  line = 0,
  arc_cw,
  arc_ccw,
  dwell,
  line_exact_stop,
  arc_cw_exact_stop,
  arc_ccw_exact_stop,
  rapid,             // a line that is a rapid (G0): it does not wait for the spindle (motion/segment.hpp)
  rapid_exact_stop,
  pause,             // a program pause (M0, M1, M6): no fields, no tail (motion/segment.hpp Segment::pause)
  spindle_forward,   // a program's spindle start or new speed (M3, S): x = rpm / kSpindleRpmPerX; no tail
  spindle_reverse,   // M4
  spindle_stop,      // M5: no fields, no tail
  tool_change,       // a pause (M6) whose cycle_start puts its tool in the spindle: x = tool / kToolPerX; no tail
  probe_toward_or_error,  // G38.2: a probe line (motion/probe_move.hpp), with its tail (feed) and SEGMENT_Z
  probe_toward,           // G38.3
  probe_away_or_error,    // G38.4
  probe_away,             // G38.5
  line_per_rev,           // a feed line per spindle revolution (G95, Segment::feed_mm_rev): its tail's feed is the
                          // path speed at the programmed spindle speed, centre_normal the feed in mm/rev / kFeedRevPerNormal
  line_per_rev_exact_stop,
  line_per_rev_depth,     // a feed line per revolution along a boring pass's depth (Segment::overhang_at_end_mm):
                          // the node's boring schedule at the bar's overhang, centre_normal the overhang at the end
  line_per_rev_depth_exact_stop,
};
inline constexpr std::uint8_t kWireKindCount = 22;

// A feed per revolution in SEGMENT_TAIL.centre_normal: 1 mm of the field is 0.01 mm/rev, so its
// 0.1 um step is 1e-6 mm/rev (up to 8.38 mm/rev).
inline constexpr double kFeedRevPerNormal = 0.01;

constexpr bool is_per_rev_depth_kind(WireKind k) noexcept {
  return k == WireKind::line_per_rev_depth || k == WireKind::line_per_rev_depth_exact_stop;
}
constexpr bool is_per_rev_kind(WireKind k) noexcept {
  return k == WireKind::line_per_rev || k == WireKind::line_per_rev_exact_stop || is_per_rev_depth_kind(k);
}

// The probe kinds in ProbeKind's order from probe_toward_or_error.
constexpr bool is_probe_kind(WireKind k) noexcept {
  return k >= WireKind::probe_toward_or_error && k <= WireKind::probe_away;
}

// The axis SEGMENT_Z carries: the one a program moves beyond the XY plane.
inline constexpr std::size_t kProgramZ = hal::index(hal::Axis::z);

// A tool change's tool in SEGMENT.x: one tool per 0.1 um step (tools 0..8,388,607).
inline constexpr double kToolPerX = 1e4;

// A spindle start's speed in SEGMENT.x: 1 mm of the field is 1000 rpm, so its 0.1 um step is 0.1 rpm
// (up to 838,860 rpm).
inline constexpr double kSpindleRpmPerX = 1000.0;

constexpr bool wire_kind_has_tail(WireKind k) noexcept {
  return k == WireKind::line || k == WireKind::arc_cw || k == WireKind::arc_ccw || k == WireKind::line_exact_stop ||
         k == WireKind::arc_cw_exact_stop || k == WireKind::arc_ccw_exact_stop || k == WireKind::rapid ||
         k == WireKind::rapid_exact_stop || is_probe_kind(k) || is_per_rev_kind(k);
}

// The offset of an arc's centre from the chord's midpoint, in the chord's frame.
struct ChordCentre {
  double normal_mm = 0.0;  // along the left normal of start -> end
  double along_mm = 0.0;   // along start -> end
};

// Chord shorter than this has no direction to measure the centre against.
inline constexpr double kMinChordMm = 1e-6;

// false (out untouched) when start and end are closer than kMinChordMm.
// In `plane`'s two axes (the others of centre_mm are not touched).
bool chord_centre(const motion::PlanePoint& start_mm, const motion::PlanePoint& end_mm,
                  const motion::PlanePoint& centre_mm, motion::ArcPlane plane, ChordCentre& out) noexcept;
bool centre_from_chord(const motion::PlanePoint& start_mm, const motion::PlanePoint& end_mm, const ChordCentre& c,
                       motion::ArcPlane plane, motion::PlanePoint& centre_mm) noexcept;

// A position as the wire carries it (rounded to 0.1 um), exactly as the node decodes it; held to
// +-838 mm (what does not fit is refused by encode_segment()).
double wire_position_mm(double mm) noexcept;

struct SegmentFrames {
  hal::CanFrame head{};  // SEGMENT
  // Sent between head and tail: SEGMENT_Z (lines and XY arcs whose Z changes) or
  // SEGMENT_PLANE (every arc in G18 or G19).
  hal::CanFrame z{};
  hal::CanFrame tail{};  // SEGMENT_TAIL (lines and arcs)
  bool has_z = false;    // z holds a frame to send
  bool has_tail = false;
  motion::PlanePoint end_mm{};  // the end point as sent (the next element's start on the node)
};

// Host side. `start_mm` is where the node will start the element (the
// previous element's end_mm as sent, or where the table stands). nullptr
// on success; otherwise the field that cannot carry the element's value
// (out is then unspecified): an end point beyond the i24 range, a feed
// outside 0.01..655.35 mm/s, a feed per revolution on anything but a
// feed line or one that rounds to 0 or beyond 8.38 mm/rev, a dwell beyond 838 s, a spindle speed that
// rounds to 0 or beyond 838,860 rpm, an arc without a chord or with its
// centre too far off the bisector, a plane outside motion::ArcPlane. Lines
// and XY arcs whose end Z (as sent) differs from start_mm's get a
// SEGMENT_Z, arcs in another plane a SEGMENT_PLANE; axes beyond X, Y and Z
// are not carried (they stay where the element starts).
const FieldDef* encode_segment(const motion::Segment& segment, const motion::PlanePoint& start_mm, std::uint8_t node,
                               std::uint8_t tag, SegmentFrames& out) noexcept;
// Host side: a manual tool change (M6) that puts `tool` in the spindle, a pause
// at `at_mm`. nullptr, or &x for a tool outside 0..8,388,607.
const FieldDef* encode_tool_change(int tool, const motion::PlanePoint& at_mm, std::uint8_t node, std::uint8_t tag,
                                   SegmentFrames& out) noexcept;

// Node side: the SEGMENT frame. false when its kind is not one of WireKind
// (refuse out_of_range naming `kind`).
struct SegmentHead {
  WireKind kind = WireKind::line;
  motion::PlanePoint end_mm{};  // lines and arcs: x and y (Z from SEGMENT_Z or the start)
  bool has_z = false;           // a SEGMENT_Z or SEGMENT_PLANE came for it
  double end_z_mm = 0.0;
  motion::ArcPlane plane = motion::ArcPlane::xy;  // arcs: from SEGMENT_PLANE
  double dwell_s = 0.0;         // dwells
  double spindle_rpm = 0.0;     // spindle starts
  std::int32_t tool = 0;        // tool changes
};
bool decode_head(const hal::CanFrame& head, SegmentHead& out) noexcept;

// Node side: a SEGMENT_Z completes `head` (a line or arc waiting for its tail
// that has no Z yet). false (head untouched) otherwise: refuse not_ready.
bool decode_z(const hal::CanFrame& z, SegmentHead& head) noexcept;

// Node side: a SEGMENT_PLANE completes `head`. ok, or (head untouched) the
// refusal: not_ready when head has its Z already (a SEGMENT_Z or another
// SEGMENT_PLANE) or waits for no tail; out_of_range (naming `plane`) for a
// plane outside motion::ArcPlane or an element that is not an arc.
ErrorCode decode_plane(const hal::CanFrame& frame, SegmentHead& head) noexcept;

// The element a head (and, for lines and arcs, its tail) describes, starting
// at start_mm. false only for an arc whose chord is shorter than kMinChordMm
// (refuse bad_arc naming `centre_normal`); the queue checks everything else.
bool decode_segment(const SegmentHead& head, const hal::CanFrame* tail, const motion::PlanePoint& start_mm,
                    motion::Segment& out) noexcept;

}  // namespace tnv::fw::can
