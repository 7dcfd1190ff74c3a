// SEGMENT / SEGMENT_Z / SEGMENT_TAIL: what the host encodes is what the node decodes,
// to the wire's 0.1 um, and what does not fit is refused naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"
#include "firmware/can/segment_wire.hpp"

namespace tnv::fw::can {
namespace {

using motion::PlanePoint;
using motion::Segment;
using motion::SegmentKind;

constexpr double kWireMm = 1e-4;  // the positions' scale

Segment round_trip(const Segment& s, const PlanePoint& start) {
  SegmentFrames frames;
  EXPECT_EQ(encode_segment(s, start, 1, 0x13, frames), nullptr);
  EXPECT_EQ(frames.head.data[0], 0x13);
  SegmentHead head;
  EXPECT_TRUE(decode_head(frames.head, head));
  Segment out;
  EXPECT_TRUE(decode_segment(head, frames.has_tail ? &frames.tail : nullptr, start, out));
  EXPECT_EQ(frames.has_tail, s.kind != SegmentKind::dwell);
  return out;
}

double distance(const PlanePoint& a, const PlanePoint& b) { return std::hypot(a[0] - b[0], a[1] - b[1]); }

TEST(SegmentWire, LineKeepsEndFeedAndExactStopToTheWiresResolution) {
  Segment s = motion::line_to({12.345678, -200.0000049}, 33.333);
  s.exact_stop = true;
  const Segment out = round_trip(s, {0.0, 0.0});
  EXPECT_EQ(out.kind, SegmentKind::line);
  EXPECT_TRUE(out.exact_stop);
  EXPECT_LE(std::fabs(out.end_mm[0] - 12.345678), kWireMm / 2 + 1e-12);
  EXPECT_LE(std::fabs(out.end_mm[1] + 200.0000049), kWireMm / 2 + 1e-12);
  EXPECT_NEAR(out.feed_mm_s, 33.33, 1e-9) << "feed in 0.01 mm/s steps";
  EXPECT_EQ(out.end_mm[0], wire_position_mm(12.345678)) << "the host's quantisation is the node's, bit for bit";
}

TEST(SegmentWire, ArcsOfEverySweepKeepTheirCentre) {
  const PlanePoint c{3.0, -4.0};
  const double r = 20.0;
  // quarter, just under and over a half, 350 degrees; both directions
  for (const double sweep_deg : {90.0, 179.0, 181.0, 350.0}) {
    for (const bool cw : {false, true}) {
      const double a0 = 0.3;
      const double a1 = a0 + (cw ? -1.0 : 1.0) * sweep_deg * std::numbers::pi / 180.0;
      const PlanePoint start{wire_position_mm(c[0] + r * std::cos(a0)), wire_position_mm(c[1] + r * std::sin(a0))};
      const PlanePoint end{c[0] + r * std::cos(a1), c[1] + r * std::sin(a1)};
      const Segment out = round_trip(motion::arc_to(cw, end, c, 12.5), start);
      EXPECT_EQ(out.kind, cw ? SegmentKind::arc_cw : SegmentKind::arc_ccw);
      EXPECT_LE(distance(out.centre_mm, c), 1.5 * kWireMm) << sweep_deg << " deg, cw " << cw;
      EXPECT_LE(distance(out.end_mm, end), 0.71 * kWireMm);
    }
  }
}

TEST(SegmentWire, DwellIsOneFrameWithItsTimeInTenthsOfAMillisecond) {
  const Segment out = round_trip(motion::dwell_for(2.50004), {1.0, 2.0});
  EXPECT_EQ(out.kind, SegmentKind::dwell);
  EXPECT_NEAR(out.dwell_s, 2.5, 1e-12);
}

TEST(SegmentWire, WhatDoesNotFitIsRefusedNamingTheField) {
  using namespace fields;
  SegmentFrames f;
  const PlanePoint o{0.0, 0.0};
  EXPECT_EQ(encode_segment(motion::line_to({900.0, 0.0}, 10.0), o, 1, 0x11, f), &kSegmentX) << "beyond +-838 mm";
  EXPECT_EQ(encode_segment(motion::line_to({1.0, -900.0}, 10.0), o, 1, 0x11, f), &kSegmentY);
  EXPECT_EQ(encode_segment(motion::line_to({1.0, 1.0}, 700.0), o, 1, 0x11, f), &kTailFeed) << "feed beyond 655.35";
  EXPECT_EQ(encode_segment(motion::line_to({1.0, 1.0}, 0.001), o, 1, 0x11, f), &kTailFeed) << "feed rounds to 0";
  EXPECT_EQ(encode_segment(motion::dwell_for(0.00001), o, 1, 0x11, f), &kSegmentX) << "dwell rounds to 0";
  EXPECT_EQ(encode_segment(motion::dwell_for(900.0), o, 1, 0x11, f), &kSegmentX) << "dwell beyond 838 s";
  EXPECT_EQ(encode_segment(motion::arc_to(false, o, {5.0, 0.0}, 10.0), o, 1, 0x11, f), &kTailCentreNormal)
      << "a full circle has no chord";
  // A centre 10 mm along the chord from its midpoint (a radius mismatch no queue accepts).
  EXPECT_EQ(encode_segment(motion::arc_to(false, {2.0, 0.0}, {11.0, 5.0}, 10.0), o, 1, 0x11, f), &kTailCentreAlong);
}

TEST(SegmentWire, TheNodeRefusesAnUnknownKind) {
  SegmentFrames f;
  ASSERT_EQ(encode_segment(motion::line_to({1.0, 0.0}, 1.0), {0.0, 0.0}, 1, 0x11, f), nullptr);
  write_raw(f.head, fields::kSegmentKind, kWireKindCount);
  SegmentHead head;
  EXPECT_FALSE(decode_head(f.head, head));
  write_raw(f.head, fields::kSegmentKind, kWireKindCount - 1);
  EXPECT_TRUE(decode_head(f.head, head));
  EXPECT_EQ(head.kind, WireKind::line_per_rev_depth_exact_stop);
}

// A feed per revolution (G95) travels as SEGMENT kind line_per_rev: the
// feed in mm/rev to 1e-6 in the tail's centre_normal, the path speed at the
// programmed spindle speed in its feed; only a plain feed line carries one.
TEST(SegmentWire, AFeedPerRevolutionKeepsItsFeedPerRevolution) {
  motion::Segment s = motion::line_to({0.0, 0.0, -120.0}, 8.3333);
  s.feed_mm_rev = 0.0833337;
  const PlanePoint start{0.0, 0.0, -150.0};
  SegmentFrames f;
  ASSERT_EQ(encode_segment(s, start, 1, 0x13, f), nullptr);
  EXPECT_EQ(read_raw(f.head, fields::kSegmentKind), static_cast<std::uint32_t>(WireKind::line_per_rev));
  SegmentHead head;
  ASSERT_TRUE(decode_head(f.head, head));
  ASSERT_TRUE(f.has_z);
  ASSERT_TRUE(decode_z(f.z, head));
  Segment out;
  ASSERT_TRUE(decode_segment(head, &f.tail, start, out));
  EXPECT_NEAR(out.feed_mm_rev, 0.083334, 1e-12) << "1e-6 mm/rev steps";
  EXPECT_NEAR(out.feed_mm_s, 8.33, 1e-9);
  EXPECT_NEAR(out.end_mm[2], -120.0, 1e-9);
  EXPECT_FALSE(out.exact_stop);
  EXPECT_FALSE(out.rapid);
  s.exact_stop = true;
  EXPECT_TRUE(round_trip(s, start).exact_stop);
  EXPECT_GT(round_trip(s, start).feed_mm_rev, 0.0);
  EXPECT_EQ(round_trip(motion::line_to({1.0, 0.0}, 5.0), {0.0, 0.0}).feed_mm_rev, 0.0) << "G94 stays per minute";
  // Not carried: a rapid or an arc per revolution, one that rounds to nothing or does not fit.
  motion::Segment rapid = s;
  rapid.rapid = true;
  EXPECT_EQ(encode_segment(rapid, start, 1, 1, f), &fields::kSegmentKind);
  motion::Segment arc = motion::arc_to(false, {10.0, 0.0}, {5.0, 0.0}, 10.0);
  arc.feed_mm_rev = 0.1;
  EXPECT_EQ(encode_segment(arc, {0.0, 0.0}, 1, 1, f), &fields::kSegmentKind);
  motion::Segment tiny = s;
  tiny.feed_mm_rev = 4e-7;
  EXPECT_EQ(encode_segment(tiny, start, 1, 1, f), &fields::kTailCentreNormal);
  motion::Segment huge = s;
  huge.feed_mm_rev = 9.0;
  EXPECT_EQ(encode_segment(huge, start, 1, 1, f), &fields::kTailCentreNormal);
}

// A feed per revolution along a boring pass's depth travels as SEGMENT kind
// line_per_rev_depth: the bar's overhang at the end to 0.1 um in the tail's
// centre_normal; the node takes the infeed from its planner's schedule.
TEST(SegmentWire, AFeedAlongTheDepthKeepsTheOverhangAtItsEnd) {
  motion::Segment s = motion::line_to({0.0, 0.0, -299.0}, 50.0);
  s.overhang_at_end_mm = 314.00004;
  const PlanePoint start{0.0, 0.0, -15.0};
  SegmentFrames f;
  ASSERT_EQ(encode_segment(s, start, 1, 0x14, f), nullptr);
  EXPECT_EQ(read_raw(f.head, fields::kSegmentKind), static_cast<std::uint32_t>(WireKind::line_per_rev_depth));
  SegmentHead head;
  ASSERT_TRUE(decode_head(f.head, head));
  ASSERT_TRUE(f.has_z);
  ASSERT_TRUE(decode_z(f.z, head));
  Segment out;
  ASSERT_TRUE(decode_segment(head, &f.tail, start, out));
  EXPECT_NEAR(out.overhang_at_end_mm, 314.0, 1e-9);
  EXPECT_EQ(out.feed_mm_rev, 0.0);
  EXPECT_TRUE(out.per_rev_along_depth());
  EXPECT_NEAR(out.feed_mm_s, 50.0, 1e-9);
  EXPECT_NEAR(out.end_mm[2], -299.0, 1e-9);
  EXPECT_FALSE(out.exact_stop);
  s.exact_stop = true;
  ASSERT_EQ(encode_segment(s, start, 1, 0x14, f), nullptr);
  EXPECT_EQ(read_raw(f.head, fields::kSegmentKind),
            static_cast<std::uint32_t>(WireKind::line_per_rev_depth_exact_stop));
  EXPECT_TRUE(round_trip(s, start).exact_stop);
  EXPECT_TRUE(round_trip(s, start).per_rev_along_depth());
  // Not carried: an overhang that rounds to nothing or does not fit, a rapid along the depth.
  motion::Segment tiny = s;
  tiny.overhang_at_end_mm = 4e-5;
  EXPECT_EQ(encode_segment(tiny, start, 1, 1, f), &fields::kTailCentreNormal);
  motion::Segment huge = s;
  huge.overhang_at_end_mm = 900.0;
  EXPECT_EQ(encode_segment(huge, start, 1, 1, f), &fields::kTailCentreNormal);
  motion::Segment rapid = s;
  rapid.rapid = true;
  EXPECT_EQ(encode_segment(rapid, start, 1, 1, f), &fields::kSegmentKind);
}

// Each probe kind (G38.2-G38.5) travels as its own SEGMENT kind with a tail
// and, moving Z, a SEGMENT_Z; the node rebuilds the same probe line.
TEST(SegmentWire, AProbeMoveKeepsItsKindEndPointAndFeed) {
  using motion::ProbeKind;
  for (const ProbeKind kind :
       {ProbeKind::toward_or_error, ProbeKind::toward, ProbeKind::away_or_error, ProbeKind::away}) {
    SCOPED_TRACE(static_cast<int>(kind));
    const motion::PlanePoint start{1.0, 2.0, -3.0};
    const motion::Segment probe = motion::probe_to(kind, {1.0, 2.0, -13.25}, 2.5);
    SegmentFrames f;
    ASSERT_EQ(encode_segment(probe, start, 1, 0x21, f), nullptr);
    ASSERT_TRUE(f.has_tail);
    ASSERT_TRUE(f.has_z);
    SegmentHead head;
    ASSERT_TRUE(decode_head(f.head, head));
    ASSERT_TRUE(decode_z(f.z, head));
    motion::Segment out;
    ASSERT_TRUE(decode_segment(head, &f.tail, start, out));
    EXPECT_EQ(out.probe, kind);
    EXPECT_EQ(out.kind, motion::SegmentKind::line);
    EXPECT_TRUE(out.exact_stop);
    EXPECT_FALSE(out.rapid);
    EXPECT_NEAR(out.end_mm[2], -13.25, 1e-9);
    EXPECT_NEAR(out.feed_mm_s, 2.5, 1e-9);
  }
}

// A tool change (M6) is one frame, a pause on the node that carries its tool exactly.
TEST(SegmentWire, AToolChangeIsAPauseThatCarriesItsTool) {
  for (const int tool : {0, 1, 7, 99999, 8388607}) {
    SegmentFrames f;
    ASSERT_EQ(encode_tool_change(tool, {1.5, -2.0}, 1, 0x11, f), nullptr) << tool;
    EXPECT_FALSE(f.has_tail);
    EXPECT_EQ(f.end_mm, (PlanePoint{1.5, -2.0})) << "the next element starts where the change rests";
    SegmentHead head;
    ASSERT_TRUE(decode_head(f.head, head));
    EXPECT_EQ(head.kind, WireKind::tool_change);
    EXPECT_EQ(head.tool, tool);
    motion::Segment back;
    ASSERT_TRUE(decode_segment(head, nullptr, {1.5, -2.0}, back));
    EXPECT_TRUE(back.pause);
    EXPECT_EQ(back.dwell_s, 0.0);
  }
  SegmentFrames f;
  EXPECT_EQ(encode_tool_change(-1, {0.0, 0.0}, 1, 0x11, f), &fields::kSegmentX);
  EXPECT_EQ(encode_tool_change(8388608, {0.0, 0.0}, 1, 0x11, f), &fields::kSegmentX);
}

// A program pause is one frame of its own kind and comes back a pause, not a dwell that runs out.
TEST(SegmentWire, APauseIsOneFrameAndStaysAPause) {
  SegmentFrames f;
  ASSERT_EQ(encode_segment(motion::pause_here(7), {1.5, -2.0}, 1, 0x11, f), nullptr);
  EXPECT_FALSE(f.has_tail);
  EXPECT_EQ(f.end_mm, (PlanePoint{1.5, -2.0})) << "the next element starts where the pause rests";
  SegmentHead head;
  ASSERT_TRUE(decode_head(f.head, head));
  EXPECT_EQ(head.kind, WireKind::pause);
  EXPECT_FALSE(wire_kind_has_tail(head.kind));
  motion::Segment back;
  ASSERT_TRUE(decode_segment(head, nullptr, {1.5, -2.0}, back));
  EXPECT_TRUE(back.pause);
  EXPECT_EQ(back.kind, motion::SegmentKind::dwell);
  EXPECT_EQ(back.dwell_s, 0.0);
  // A plain dwell is not a pause.
  ASSERT_EQ(encode_segment(motion::dwell_for(0.5), {0.0, 0.0}, 1, 0x11, f), nullptr);
  ASSERT_TRUE(decode_head(f.head, head));
  ASSERT_TRUE(decode_segment(head, nullptr, {0.0, 0.0}, back));
  EXPECT_FALSE(back.pause);
}

// A program's spindle commands are one frame each, the speed to 0.1 rpm.
TEST(SegmentWire, SpindleCommandsKeepTheirDirectionAndSpeed) {
  using motion::SpindleChange;
  for (const SpindleChange c : {SpindleChange::forward, SpindleChange::reverse, SpindleChange::stop}) {
    SegmentFrames f;
    ASSERT_EQ(encode_segment(motion::spindle_here(c, 12345.67), {1.0, 2.0}, 1, 0x11, f), nullptr);
    EXPECT_FALSE(f.has_tail);
    EXPECT_EQ(f.end_mm, (PlanePoint{1.0, 2.0}));
    SegmentHead head;
    ASSERT_TRUE(decode_head(f.head, head));
    motion::Segment back;
    ASSERT_TRUE(decode_segment(head, nullptr, {1.0, 2.0}, back));
    EXPECT_EQ(back.spindle, c);
    EXPECT_FALSE(back.pause);
    EXPECT_EQ(back.kind, motion::SegmentKind::dwell);
    EXPECT_NEAR(back.spindle_rpm, c == SpindleChange::stop ? 0.0 : 12345.7, 1e-6);
  }
  SegmentFrames f;
  EXPECT_EQ(encode_segment(motion::spindle_here(SpindleChange::forward, 900'000.0), {0.0, 0.0}, 1, 0x11, f), &fields::kSegmentX)
      << "beyond 838,860 rpm";
  EXPECT_EQ(encode_segment(motion::spindle_here(SpindleChange::forward, 0.04), {0.0, 0.0}, 1, 0x11, f), &fields::kSegmentX)
      << "rounds to no speed";
}

// A rapid (G0) keeps its kind over the wire, with and without an exact
// stop: the node must not make it a feed move that waits for the spindle,
// nor a feed move a rapid that does not.
TEST(SegmentWire, ARapidStaysARapidAndAFeedMoveStaysAFeedMove) {
  for (const bool exact : {false, true}) {
    for (const bool rapid : {false, true}) {
      motion::Segment s = motion::line_to({2.0, -1.0}, 25.0);
      s.rapid = rapid;
      s.exact_stop = exact;
      SegmentFrames f;
      ASSERT_EQ(encode_segment(s, {0.0, 0.0}, 1, 0x11, f), nullptr);
      SegmentHead head;
      ASSERT_TRUE(decode_head(f.head, head));
      motion::Segment back;
      ASSERT_TRUE(decode_segment(head, &f.tail, {0.0, 0.0}, back));
      EXPECT_EQ(back.rapid, rapid);
      EXPECT_EQ(back.exact_stop, exact);
      EXPECT_EQ(back.kind, motion::SegmentKind::line);
      EXPECT_NEAR(back.feed_mm_s, 25.0, 0.005);
    }
  }
}

TEST(SegmentWire, ChordCoordinatesInvertExactly) {
  const PlanePoint s{1.25, -3.5};
  const PlanePoint e{-7.0, 2.0};
  const PlanePoint c{0.5, 9.0};
  ChordCentre cc;
  ASSERT_TRUE(chord_centre(s, e, c, motion::ArcPlane::xy, cc));
  PlanePoint back{};
  ASSERT_TRUE(centre_from_chord(s, e, cc, motion::ArcPlane::xy, back));
  EXPECT_NEAR(distance(back, c), 0.0, 1e-12);
  EXPECT_FALSE(chord_centre(s, s, c, motion::ArcPlane::xy, cc)) << "no chord, no frame to measure the centre in";
  // In G18 the chord is Z then X; Y (the helix' axis) is not the centre's business.
  const PlanePoint s3{1.25, 40.0, -3.5};
  const PlanePoint e3{-7.0, -12.0, 2.0};
  const PlanePoint c3{0.5, 7.0, 9.0};
  ASSERT_TRUE(chord_centre(s3, e3, c3, motion::ArcPlane::zx, cc));
  PlanePoint back3{0.0, 5.0, 0.0};
  ASSERT_TRUE(centre_from_chord(s3, e3, cc, motion::ArcPlane::zx, back3));
  EXPECT_NEAR(back3[0], 0.5, 1e-12);
  EXPECT_NEAR(back3[2], 9.0, 1e-12);
  EXPECT_EQ(back3[1], 5.0) << "the axis beyond the plane is left as it was";
  EXPECT_FALSE(chord_centre(s3, PlanePoint{1.25, 0.0, -3.5}, c3, motion::ArcPlane::zx, cc))
      << "start and end the same in Z and X: no chord in G18, whatever Y does";
}

// The node's side of an element with its Z frame, as the program stream takes it: head, Z (when sent), tail.
Segment round_trip_z(const Segment& s, const PlanePoint& start, SegmentFrames& frames) {
  EXPECT_EQ(encode_segment(s, start, 1, 0x13, frames), nullptr);
  SegmentHead head;
  EXPECT_TRUE(decode_head(frames.head, head));
  if (frames.has_z) {
    EXPECT_EQ(frames.z.data[0], 0x13) << "the Z frame carries its element's tag";
    if (frames.z.dlc == fields::kSegmentPlaneMsg.dlc) EXPECT_EQ(decode_plane(frames.z, head), ErrorCode::ok);
    else EXPECT_TRUE(decode_z(frames.z, head));
  }
  Segment out;
  EXPECT_TRUE(decode_segment(head, frames.has_tail ? &frames.tail : nullptr, start, out));
  return out;
}

TEST(SegmentWire, ALineThatMovesZSendsAThirdFrameAndOneInThePlaneKeepsTwo) {
  const PlanePoint start{1.0, 2.0, -5.0};
  SegmentFrames f;
  Segment out = round_trip_z(motion::line_to({11.0, 7.0, -7.123456}, 20.0), start, f);
  EXPECT_TRUE(f.has_z);
  EXPECT_EQ(f.z.dlc, fields::kSegmentZMsg.dlc);
  EXPECT_LE(std::fabs(out.end_mm[kProgramZ] + 7.123456), kWireMm / 2 + 1e-12);
  EXPECT_EQ(out.end_mm[kProgramZ], f.end_mm[kProgramZ]) << "the host's end point as sent is the node's";
  EXPECT_EQ(out.end_mm[kProgramZ], wire_position_mm(-7.123456));
  EXPECT_NEAR(out.end_mm[0], 11.0, 1e-12);

  // A plunge: X and Y stay, Z alone moves.
  out = round_trip_z(motion::line_to({1.0, 2.0, -9.5}, 5.0), start, f);
  EXPECT_TRUE(f.has_z);
  EXPECT_EQ(out.end_mm, (PlanePoint{1.0, 2.0, -9.5}));

  // In the plane at the start's Z: two frames, and the node keeps Z where the element starts (not 0).
  out = round_trip_z(motion::line_to({4.0, 2.0, -5.0}, 20.0), start, f);
  EXPECT_FALSE(f.has_z);
  EXPECT_TRUE(f.has_tail);
  EXPECT_EQ(out.end_mm[kProgramZ], -5.0);
  EXPECT_EQ(f.end_mm[kProgramZ], -5.0);
}

TEST(SegmentWire, AHelixCarriesItsCentreAndItsZ) {
  const PlanePoint c{3.0, -4.0, 0.0};
  const double r = 10.0;
  for (const bool cw : {false, true}) {
    const PlanePoint start{c[0] + r, c[1], -2.0};
    const PlanePoint end{c[0], c[1] + (cw ? -r : r), -3.25};
    SegmentFrames f;
    const Segment out = round_trip_z(motion::arc_to(cw, end, c, 8.0), start, f);
    EXPECT_TRUE(f.has_z);
    EXPECT_EQ(out.kind, cw ? SegmentKind::arc_cw : SegmentKind::arc_ccw);
    EXPECT_LE(distance(out.centre_mm, c), 1.5 * kWireMm);
    EXPECT_NEAR(out.end_mm[kProgramZ], -3.25, 1e-12);
    EXPECT_NEAR(out.feed_mm_s, 8.0, 1e-12);
  }
}

TEST(SegmentWire, AZBeyondTheWireOrWithoutItsElementIsRefused) {
  SegmentFrames f;
  const PlanePoint o{0.0, 0.0, 0.0};
  EXPECT_EQ(encode_segment(motion::line_to({1.0, 1.0, -900.0}, 10.0), o, 1, 0x11, f), &fields::kSegmentZField)
      << "beyond +-838 mm";
  ASSERT_EQ(encode_segment(motion::line_to({1.0, 1.0, -3.0}, 10.0), o, 1, 0x11, f), nullptr);
  SegmentHead head;
  ASSERT_TRUE(decode_head(f.head, head));
  ASSERT_TRUE(decode_z(f.z, head));
  const SegmentHead once = head;
  EXPECT_FALSE(decode_z(f.z, head)) << "a second Z for one element";
  EXPECT_EQ(head.end_z_mm, once.end_z_mm);
  SegmentFrames dwell;
  ASSERT_EQ(encode_segment(motion::dwell_for(1.0), o, 1, 0x12, dwell), nullptr);
  EXPECT_FALSE(dwell.has_z) << "a dwell stays where the path is";
  SegmentHead d;
  ASSERT_TRUE(decode_head(dwell.head, d));
  EXPECT_FALSE(decode_z(f.z, d)) << "a dwell has no Z to take";
  EXPECT_FALSE(d.has_z);
}

// G18 and G19 arcs: SEGMENT_PLANE in SEGMENT_Z's place (the plane and Z,
// always), the centre in that plane's chord frame; XY elements unchanged.
TEST(SegmentWire, AnArcInG18OrG19CarriesItsPlaneZAndCentre) {
  for (const motion::ArcPlane plane : {motion::ArcPlane::zx, motion::ArcPlane::yz}) {
    for (const bool cw : {false, true}) {
      const motion::PlaneAxes pa = motion::plane_axes(plane);
      PlanePoint c{3.0, -4.0, -20.0};
      PlanePoint start = c;
      start[pa.first] += 10.0;
      PlanePoint end = c;
      end[pa.second] += cw ? -10.0 : 10.0;
      const std::size_t helix = plane == motion::ArcPlane::zx ? 1 : 0;
      start[helix] = 1.0;
      end[helix] = -2.5;
      c[helix] = start[helix];
      SegmentFrames f;
      const Segment out = round_trip_z(motion::arc_to(cw, end, c, 8.0, 0, plane), start, f);
      ASSERT_TRUE(f.has_z);
      EXPECT_EQ(f.z.dlc, fields::kSegmentPlaneMsg.dlc);
      EXPECT_EQ(f.head.dlc, fields::kSegmentMsg.dlc);
      EXPECT_EQ(f.tail.dlc, fields::kSegmentTailMsg.dlc);
      EXPECT_EQ(out.plane, plane);
      EXPECT_EQ(out.kind, cw ? SegmentKind::arc_cw : SegmentKind::arc_ccw);
      EXPECT_LE(distance(out.centre_mm, c), 1.5 * kWireMm);
      for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(out.end_mm[i], end[i], kWireMm) << i;
      EXPECT_EQ(out.end_mm, f.end_mm) << "the host's end point as sent is the node's";
    }
  }
  // An XY arc keeps its two frames (no Z change) and is an XY arc on the node.
  SegmentFrames f;
  const Segment xy = round_trip_z(motion::arc_to(false, {0.0, 10.0, -1.0}, {0.0, 0.0, -1.0}, 8.0), {10.0, 0.0, -1.0}, f);
  EXPECT_FALSE(f.has_z);
  EXPECT_EQ(xy.plane, motion::ArcPlane::xy);
}

TEST(SegmentWire, AnUnknownOrMisplacedPlaneIsRefusedAndChangesNothing) {
  const PlanePoint o{0.0, 0.0, -10.0};
  SegmentFrames f;
  ASSERT_EQ(encode_segment(motion::arc_to(false, {0.0, 0.0, 0.0}, {0.0, 0.0, -5.0}, 8.0, 0, motion::ArcPlane::zx),
                           o, 1, 0x21, f),
            nullptr);
  SegmentHead head;
  ASSERT_TRUE(decode_head(f.head, head));
  const SegmentHead before = head;
  hal::CanFrame bad = f.z;
  bad.data[fields::kPlaneField.byte_offset] = motion::kArcPlaneCount;  // no such plane
  EXPECT_EQ(decode_plane(bad, head), ErrorCode::out_of_range);
  EXPECT_FALSE(head.has_z);
  EXPECT_EQ(head.plane, before.plane);
  // On a line: a plane is for arcs only.
  SegmentFrames line;
  ASSERT_EQ(encode_segment(motion::line_to({1.0, 1.0, -3.0}, 10.0), o, 1, 0x22, line), nullptr);
  SegmentHead lh;
  ASSERT_TRUE(decode_head(line.head, lh));
  EXPECT_EQ(decode_plane(f.z, lh), ErrorCode::out_of_range);
  EXPECT_FALSE(lh.has_z);
  // After a SEGMENT_Z, or a second one: not_ready.
  ASSERT_EQ(decode_plane(f.z, head), ErrorCode::ok);
  EXPECT_EQ(decode_plane(f.z, head), ErrorCode::not_ready);
  EXPECT_FALSE(decode_z(line.z, head)) << "a SEGMENT_Z after the plane";
  SegmentHead zh;
  ASSERT_TRUE(decode_head(f.head, zh));
  ASSERT_TRUE(decode_z(line.z, zh));
  EXPECT_EQ(decode_plane(f.z, zh), ErrorCode::not_ready);
  // The host refuses a plane it cannot name.
  EXPECT_EQ(encode_segment(motion::arc_to(false, {0.0, 0.0, 0.0}, {0.0, 0.0, -5.0}, 8.0, 0,
                                          static_cast<motion::ArcPlane>(9)),
                           o, 1, 0x23, f),
            &fields::kPlaneField);
}

}  // namespace
}  // namespace tnv::fw::can
