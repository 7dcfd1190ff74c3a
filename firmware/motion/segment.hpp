#pragma once
// One programmed path element as a producer (G-code, CAN stream, the circle,
// move and jog generators) hands it to the motion queue. Positions are
// absolute table coordinates; a line or arc starts where the previous
// element ended.
#include <array>
#include <cstddef>
#include <cstdint>

#include "firmware/motion/probe_move.hpp"
#include "hal/axis.hpp"
#include "hal/listed_enum.hpp"

namespace tnv::fw::motion {

using PlanePoint = std::array<double, hal::kAxisCount>;  // a point on every axis, mm, in axis index order

enum class SegmentKind : std::uint8_t { line = 0, arc_cw = 1, arc_ccw = 2, dwell = 3 };

// The plane of an arc (G17, G18, G19), named by its two axes in the order
// that makes counter-clockwise the turn from the first towards the second,
// as RS274/NGC looks at it from the positive third axis: xy (G17), zx (G18),
// yz (G19). The third axis (and any other) moves linearly with the angle: a
// helix. Wire values (SEGMENT_PLANE.plane): append, never renumber.
#define TNV_ARC_PLANES(X) X(xy) X(zx) X(yz)
TNV_LISTED_ENUM(ArcPlane, TNV_ARC_PLANES)

struct PlaneAxes {
  std::size_t first = 0;   // the angle is measured from this axis ...
  std::size_t second = 1;  // ... towards this one
};

constexpr PlaneAxes plane_axes(ArcPlane plane) noexcept {
  switch (plane) {
    case ArcPlane::zx: return {hal::index(hal::Axis::z), hal::index(hal::Axis::x)};
    case ArcPlane::yz: return {hal::index(hal::Axis::y), hal::index(hal::Axis::z)};
    case ArcPlane::xy: break;
  }
  return {hal::index(hal::Axis::x), hal::index(hal::Axis::y)};
}

constexpr bool in_plane(PlaneAxes p, std::size_t axis) noexcept { return axis == p.first || axis == p.second; }

// A program's spindle command (S, M3, M4, M5) carried in its place in the queue.
enum class SpindleChange : std::uint8_t { none = 0, forward, reverse, stop };

struct Segment {
  SegmentKind kind = SegmentKind::line;
  PlanePoint end_mm{};     // line and arc end point
  PlanePoint centre_mm{};  // arc centre in its plane (end == start there: a full circle)
  ArcPlane plane = ArcPlane::xy;  // arcs: the plane of the circle (a plane value outside ArcPlane: bad_kind)
  double feed_mm_s = 0.0;  // path speed for this element (ignored by a dwell)
  double dwell_s = 0.0;    // dwell only
  bool exact_stop = false; // come to rest at the end before the next element
  // > 0: a profiled element (lines and arcs): it starts and ends at rest and
  // its path speed follows the S1 protocol's time law, raised-cosine ramps
  // of ramp_s up to feed_mm_s and back (firmware/motion/profiled_run.hpp),
  // instead of the look-ahead planner's S-curve. The circle and move
  // producers use it; G-code and streamed programs do not.
  double ramp_s = 0.0;
  std::uint32_t tag = 0;   // producer's reference (G-code line number), reported back
  // A rapid (G0): positioning, not cutting. Every other line and arc is a
  // feed move, which starts only while the spindle permits it (commanded
  // off, or on and at speed: firmware/spindle/spindle_control.hpp). A rapid
  // followed by a feed move ends at rest (the queue makes it an exact
  // stop), so the feed move can wait for the spindle there.
  bool rapid = false;
  // A dwell that is a program pause (M0, M1, M6's manual tool change): the
  // path point comes to rest at it (the element before it ends at rest, as
  // before any dwell) and it stays at the front of the queue, the motion
  // core paused, until the producer releases it
  // (MotionInterpolator::release_pause()). dwell_s is 0.
  bool pause = false;
  // A dwell that is a spindle command of the program (S, M3, M4, M5): like
  // a pause it is reached at rest and waits at the front, and the tick task
  // carries it out (spindle_rpm for a start; a start while turning is a new
  // speed or direction) the tick the motion core rests at it, then the
  // program goes on (MotionInterpolator::spindle_change_due()). As
  // LinuxCNC's task waits for motion to finish before a spindle command.
  SpindleChange spindle = SpindleChange::none;
  double spindle_rpm = 0.0;
  // A probe move (G38.2-G38.5, probe_move.hpp): a feed line that starts at
  // rest with the input checked, ends when the probe input changes
  // (braking on the path) or at its end, and ends at rest. Nothing may be
  // queued behind it until its outcome is known (probe_pending).
  ProbeKind probe = ProbeKind::none;
  // > 0: a feed per revolution (G95, mm/rev), a feed line synchronised to
  // the spindle: its path speed is feed_mm_rev times the spindle's measured
  // revolutions per second, 0 while the spindle is not at speed
  // (spindle_synced_feed.hpp). feed_mm_s is then its speed at the
  // programmed spindle speed, what the look-ahead plans with; the tick
  // scales it by measured over programmed speed through the feed override
  // (MotionInterpolator::set_spindle_rpm). Only plain feed lines (no
  // rapid, probe or profiled element).
  double feed_mm_rev = 0.0;
  // > 0: a feed per revolution along a boring pass's depth (S4 eq. (3) on
  // the node): the bar's overhang at end_mm; at the path point's Z it is
  // this less (Z - end Z) (the bar reaches deeper as Z falls). The feed per
  // revolution is then the node's boring schedule at that overhang
  // (MotionInterpolator::set_depth_infeed), evaluated every tick, not
  // feed_mm_rev (0); feed_mm_s is the path speed of the line's largest
  // infeed at the programmed spindle speed (the look-ahead's upper bound).
  double overhang_at_end_mm = 0.0;

  bool profiled() const noexcept { return ramp_s > 0.0; }
  bool per_rev_along_depth() const noexcept { return overhang_at_end_mm > 0.0; }
  bool per_rev() const noexcept { return feed_mm_rev > 0.0 || per_rev_along_depth(); }
};

// An element that is not motion: a pause or a spindle command (the motion core holds it at the front).
constexpr bool is_program_action(const Segment& s) noexcept { return s.pause || s.spindle != SpindleChange::none; }

// A line or arc that cuts (not a rapid, not a dwell): what the spindle's feed gate holds.
constexpr bool is_feed_move(const Segment& s) noexcept { return s.kind != SegmentKind::dwell && !s.rapid; }

constexpr Segment line_to(PlanePoint end_mm, double feed_mm_s, std::uint32_t tag = 0) noexcept {
  Segment s;
  s.kind = SegmentKind::line;
  s.end_mm = end_mm;
  s.feed_mm_s = feed_mm_s;
  s.tag = tag;
  return s;
}

constexpr Segment arc_to(bool clockwise, PlanePoint end_mm, PlanePoint centre_mm, double feed_mm_s,
                         std::uint32_t tag = 0, ArcPlane plane = ArcPlane::xy) noexcept {
  Segment s;
  s.plane = plane;
  s.kind = clockwise ? SegmentKind::arc_cw : SegmentKind::arc_ccw;
  s.end_mm = end_mm;
  s.centre_mm = centre_mm;
  s.feed_mm_s = feed_mm_s;
  s.tag = tag;
  return s;
}

constexpr Segment dwell_for(double dwell_s, std::uint32_t tag = 0) noexcept {
  Segment s;
  s.kind = SegmentKind::dwell;
  s.dwell_s = dwell_s;
  s.tag = tag;
  return s;
}

// G38.2-G38.5: a probe line to end_mm at feed_mm_s.
constexpr Segment probe_to(ProbeKind kind, PlanePoint end_mm, double feed_mm_s, std::uint32_t tag = 0) noexcept {
  Segment s = line_to(end_mm, feed_mm_s, tag);
  s.probe = kind;
  s.exact_stop = true;
  return s;
}

constexpr Segment pause_here(std::uint32_t tag = 0) noexcept {
  Segment s;
  s.kind = SegmentKind::dwell;
  s.pause = true;
  s.tag = tag;
  return s;
}

// A spindle command of a program: forward or reverse at rpm, or stop (rpm ignored).
constexpr Segment spindle_here(SpindleChange change, double rpm, std::uint32_t tag = 0) noexcept {
  Segment s;
  s.kind = SegmentKind::dwell;
  s.spindle = change;
  s.spindle_rpm = change == SpindleChange::stop ? 0.0 : rpm;
  s.tag = tag;
  return s;
}

// Why the queue refused a segment (the queue is then unchanged).
enum class SegmentRefusal : std::uint8_t {
  none = 0,
  queue_full = 1,
  not_finite = 2,          // a NaN or infinite number
  bad_kind = 3,            // unknown kind or arc plane, or a pause that is also a spindle command
  zero_length = 4,         // line or arc shorter than MotionLimits::min_segment_mm
  arc_radius_mismatch = 5, // |start - centre| and |end - centre| differ beyond the tolerance
  arc_radius_too_small = 6,
  feed_not_positive = 7,
  feed_above_limit = 8,    // feed above what the axis speed limits allow on this element
  outside_workspace = 9,   // end point outside the soft limits
  bad_dwell = 10,          // dwell time <= 0 or too long (a pause's not 0)
  bad_ramp = 11,           // ramp_s negative, on a dwell, or its two ramps longer than the element
  bad_spindle = 12,        // a spindle start's rpm not above zero or above the spindle's max_rpm
  probe_pending = 13,      // a probe move is queued or running: its outcome decides what comes next
};

constexpr const char* to_string(SegmentRefusal r) noexcept {
  switch (r) {
    case SegmentRefusal::none: return "none";
    case SegmentRefusal::queue_full: return "queue_full";
    case SegmentRefusal::not_finite: return "not_finite";
    case SegmentRefusal::bad_kind: return "bad_kind";
    case SegmentRefusal::zero_length: return "zero_length";
    case SegmentRefusal::arc_radius_mismatch: return "arc_radius_mismatch";
    case SegmentRefusal::arc_radius_too_small: return "arc_radius_too_small";
    case SegmentRefusal::feed_not_positive: return "feed_not_positive";
    case SegmentRefusal::feed_above_limit: return "feed_above_limit";
    case SegmentRefusal::outside_workspace: return "outside_workspace";
    case SegmentRefusal::bad_dwell: return "bad_dwell";
    case SegmentRefusal::bad_ramp: return "bad_ramp";
    case SegmentRefusal::bad_spindle: return "bad_spindle";
    case SegmentRefusal::probe_pending: return "probe_pending";
  }
  return "?";
}

}  // namespace tnv::fw::motion
