#include "tools/gcode/canon_segments.hpp"

#include "tools/gcode/canon_state.hpp"

#include <cmath>
#include <numbers>
#include <cstdint>
#include <string>
#include <utility>

namespace tnv::gcode {

namespace {

// The signed angle from start to end about centre in the plane, as the motion core measures an arc
// (segment_geometry.cpp): a closed arc is a full turn.
double arc_sweep_rad(const PlanePoint& start, const PlanePoint& end, const PlanePoint& centre, bool clockwise,
                     fw::motion::PlaneAxes p, double closed_mm) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  const std::size_t a = p.first, b = p.second;
  const double a0 = std::atan2(start[b] - centre[b], start[a] - centre[a]);
  double sweep = std::atan2(end[b] - centre[b], end[a] - centre[a]) - a0;
  if (std::hypot(end[a] - start[a], end[b] - start[b]) < closed_mm) return clockwise ? -two_pi : two_pi;
  if (clockwise) {
    while (sweep >= 0.0) sweep -= two_pi;
  } else {
    while (sweep <= 0.0) sweep += two_pi;
  }
  return sweep;
}

// The interpreter's plane (17, 18, 19) as the motion core's.
fw::motion::ArcPlane arc_plane(int plane) {
  return plane == 18 ? fw::motion::ArcPlane::zx : plane == 19 ? fw::motion::ArcPlane::yz : fw::motion::ArcPlane::xy;
}

using Kind = CanonMotion::Kind;
using fw::motion::Segment;
using fw::motion::SegmentRefusal;

// Offsets add up in floating point; a Z that differs by less is the same Z (no SEGMENT_Z for it).
constexpr double kSameZ_mm = 1e-6;
// A move shorter than this goes nowhere (as the old reader skipped a move to where the table is).
constexpr double kNoMove_mm = 1e-9;

class Refusal {
 public:
  explicit Refusal(std::string message) : message_(std::move(message)) {}
  const std::string& message() const { return message_; }

 private:
  std::string message_;
};

}  // namespace

void CanonSegmentSink::convert(const CanonCall& call) {
  const CanonMotion& m = call.motion;
  const auto tag = static_cast<std::uint32_t>(call.line);
  switch (m.kind) {
    case Kind::other: break;
    case Kind::traverse:
    case Kind::feed: {
      const PlanePoint end = point(m.end_mm);
      if (std::hypot(std::hypot(end[0] - at_[0], end[1] - at_[1]), end[2] - at_[2]) < kNoMove_mm) break;
      const double feed = m.kind == Kind::traverse ? options_.rapid_feed_mm_s : feed_mm_min_ / 60.0;
      if (!(feed > 0.0)) throw Refusal("feed move without a feed rate (F)");
      fw::motion::Segment line = fw::motion::line_to(end, feed, tag);
      line.rapid = m.kind == Kind::traverse;  // a rapid does not wait for the spindle
      add(line);
      break;
    }
    case Kind::arc: {
      const double feed = feed_mm_min_ / 60.0;
      if (!(feed > 0.0)) throw Refusal("arc without a feed rate (F)");
      const bool clockwise = m.turn < 0;
      const fw::motion::ArcPlane plane = arc_plane(m.plane);
      const fw::motion::PlaneAxes pa = fw::motion::plane_axes(plane);
      const PlanePoint end = point(m.end_mm);
      // The centre in the arc's plane; on the axis beyond it, where the arc starts.
      PlanePoint centre = at_;
      centre[pa.first] = m.centre_mm[pa.first];
      centre[pa.second] = m.centre_mm[pa.second];
      // P turns: the full circles first, then the arc to the end; a helix's
      // third axis is shared among them by angle, so it climbs at one pitch throughout.
      std::size_t helix = 0;
      while (fw::motion::in_plane(pa, helix)) ++helix;
      const int turns = std::abs(m.turn);
      const double last_rad =
          std::fabs(arc_sweep_rad(at_, end, centre, clockwise, pa, options_.limits.min_segment_mm));
      const double total_rad = 2.0 * std::numbers::pi * (turns - 1) + last_rad;
      const double per_rad = total_rad > 0.0 ? (end[helix] - at_[helix]) / total_rad : 0.0;
      const double h0 = at_[helix];
      for (int k = 1; k < turns; ++k) {
        PlanePoint full = at_;
        full[helix] = h0 + per_rad * 2.0 * std::numbers::pi * k;
        add(fw::motion::arc_to(clockwise, full, centre, feed, tag, plane));
      }
      add(fw::motion::arc_to(clockwise, end, centre, feed, tag, plane));
      break;
    }
    case Kind::probe: {
      if (!options_.run_probe) throw Refusal("probe move (G38.x): this run has no probe input");
      const double feed = feed_mm_min_ / 60.0;
      if (!(feed > 0.0)) throw Refusal("probe move without a feed rate (F)");
      using fw::motion::ProbeKind;
      const int g = static_cast<int>(m.value);
      const ProbeKind kind = g == 2   ? ProbeKind::toward_or_error
                             : g == 3 ? ProbeKind::toward
                             : g == 4 ? ProbeKind::away_or_error
                                      : ProbeKind::away;
      add(fw::motion::probe_to(kind, point(m.end_mm), feed, tag));
      ++program_.probes;
      break;
    }
    case Kind::spline: throw Refusal("G5.1 spline: the motion queue takes lines and arcs only");
    case Kind::rigid_tap: throw Refusal("rigid tapping (G33.1): the motion queue has no motion synchronised to the spindle");
    case Kind::dwell:
      if (m.value > 0.0) add(fw::motion::dwell_for(m.value, tag));
      break;
    case Kind::feed_rate: feed_mm_min_ = m.value; break;
    case Kind::tool_change:
      // A manual change: the program pauses for the operator. The interpreter
      // applies the new length (G43) from the next move, as LinuxCNC does.
      ++program_.tool_changes;
      add_pause(tag, PauseReason::tool_change, static_cast<int>(m.value));
      break;
    case Kind::spindle_on:
      ++program_.spindle_starts;
      spindle_direction_ = m.value < 0.0 ? -1 : 1;
      add_spindle(tag);
      break;
    case Kind::spindle_speed:
      spindle_rpm_ = m.value;
      if (spindle_direction_ != 0) add_spindle(tag);  // a new speed while it turns
      break;
    case Kind::spindle_stop:
      spindle_direction_ = 0;
      // The program's end stops a spindle the program started; the node stops it at the end anyway.
      if (m.value == 1.0 && (!sent_spindle_ || sent_spindle_->first == fw::motion::SpindleChange::stop)) break;
      add_spindle(tag);
      break;
    case Kind::coolant_on: ++program_.coolant_starts; break;
    case Kind::pause:
      if (m.value == 1.0 && !options_.canon.optional_stop) {
        ++program_.optional_stops_skipped;
        break;
      }
      add_pause(tag, m.value == 1.0    ? PauseReason::optional_stop
                     : m.value == 60.0 ? PauseReason::pallet_change
                                       : PauseReason::program_stop,
                0);
      break;
    case Kind::end: program_.ended = true; break;
  }
}

PlanePoint CanonSegmentSink::point(const std::array<double, 3>& machine_mm) const {
  PlanePoint p{machine_mm[0], machine_mm[1], machine_mm[2]};
  if (std::fabs(p[2] - at_[2]) <= kSameZ_mm) p[2] = at_[2];  // offsets' rounding is no Z move
  return p;
}

void CanonSegmentSink::add(const Segment& segment) {
  fw::motion::SegmentGeometry g;
  const SegmentRefusal r = fw::motion::prepare(segment, at_, options_.limits, g);
  if (r != SegmentRefusal::none) throw Refusal(std::string("segment refused: ") + fw::motion::to_string(r));
  program_.segments.push_back(segment);
  program_.geometry.push_back(g);
  at_ = g.end_mm;
}

// The spindle as the program has it now: on at S in its direction, or
// stopped. M3 or M4 at S0 is a spindle turning at 0 rpm: sent as a stop,
// and the next S starts it. A command that changes nothing is not sent.
void CanonSegmentSink::add_spindle(std::uint32_t tag) {
  using fw::motion::SpindleChange;
  const bool on = spindle_direction_ != 0 && spindle_rpm_ > 0.0;
  const SpindleChange change = !on ? SpindleChange::stop
                               : spindle_direction_ > 0 ? SpindleChange::forward
                                                        : SpindleChange::reverse;
  const double rpm = on ? spindle_rpm_ : 0.0;
  if (sent_spindle_ && sent_spindle_->first == change && sent_spindle_->second == rpm) return;
  add(fw::motion::spindle_here(change, rpm, tag));
  sent_spindle_ = {change, rpm};
  ++program_.spindle_changes;
}

void CanonSegmentSink::add_pause(std::uint32_t tag, PauseReason reason, int tool) {
  program_.pauses.push_back({program_.segments.size(), reason, tool});
  add(fw::motion::pause_here(tag));
}

void CanonSegmentSink::operator()(const CanonCall& call) {
  if (refused_) return;
  try {
    convert(call);
  } catch (const Refusal& e) {
    refused_ = Refused{call.line, call.file, e.message()};
  }
}

GcodeResult CanonSegmentSink::finish(const CanonRun& run) {
  GcodeResult result;
  if (run.error) {
    result.error = run.error;
  } else if (refused_) {
    result.error = GcodeError{refused_->line, 0, refused_->message,
                              refused_->file == 0 ? std::string() : run.files.at(refused_->file - 1)};
  } else {
    result.program = std::move(program_);
    result.program.lines_run = run.lines_run;
  }
  return result;
}

GcodeResult canon_segments(const CanonResult& canon, const std::array<double, 3>& start_machine_mm,
                           const GcodeOptions& options) {
  CanonSegmentSink sink(start_machine_mm, options);
  if (!canon.error)
    for (const CanonCall& call : canon.calls) sink(call);
  return sink.finish(canon);
}

}  // namespace tnv::gcode
