#include "tools/gcode/canon_segments.hpp"

#include "tools/gcode/canon_state.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

namespace tnv::gcode {

namespace {

using Kind = CanonMotion::Kind;
using fw::motion::Segment;
using fw::motion::SegmentRefusal;

// Offsets add up in floating point; a Z that differs by less is the same Z.
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
      check_z(m.end_mm);
      if (std::hypot(m.end_mm[0] - at_[0], m.end_mm[1] - at_[1]) < kNoMove_mm) break;
      const double feed = m.kind == Kind::traverse ? options_.rapid_feed_mm_s : feed_mm_min_ / 60.0;
      if (!(feed > 0.0)) throw Refusal("feed move without a feed rate (F)");
      fw::motion::Segment line = fw::motion::line_to({m.end_mm[0], m.end_mm[1]}, feed, tag);
      line.rapid = m.kind == Kind::traverse;  // a rapid does not wait for the spindle
      add(line);
      break;
    }
    case Kind::arc: {
      if (m.plane != 17)
        throw Refusal(std::string("arc in the ") + (m.plane == 18 ? "XZ plane (G18)" : "YZ plane (G19)") +
                      ": this machine has X and Y only (arcs in G17)");
      check_z(m.end_mm);
      const double feed = feed_mm_min_ / 60.0;
      if (!(feed > 0.0)) throw Refusal("arc without a feed rate (F)");
      const bool clockwise = m.turn < 0;
      const PlanePoint centre{m.centre_mm[0], m.centre_mm[1]};
      // P turns: the full circles first, then the arc to the end.
      for (int k = 1; k < std::abs(m.turn); ++k) add(fw::motion::arc_to(clockwise, {at_[0], at_[1]}, centre, feed, tag));
      add(fw::motion::arc_to(clockwise, {m.end_mm[0], m.end_mm[1]}, centre, feed, tag));
      break;
    }
    case Kind::probe: throw Refusal("probe move (G38.x): this machine has no probe input");
    case Kind::spline: throw Refusal("G5.1 spline: the motion queue takes lines and arcs only");
    case Kind::rigid_tap: throw Refusal("rigid tapping (G33.1) moves Z: this machine has X and Y only");
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

void CanonSegmentSink::check_z(const std::array<double, 3>& end) const {
  if (std::fabs(end[2] - at_[2]) > kSameZ_mm)
    throw Refusal("this move takes machine Z from " + fixed(at_[2], 4) + " to " + fixed(end[2], 4) +
                  " mm: this machine has X and Y only");
}

void CanonSegmentSink::add(const Segment& segment) {
  fw::motion::SegmentGeometry g;
  const SegmentRefusal r = fw::motion::prepare(segment, {at_[0], at_[1]}, options_.limits, g);
  if (r != SegmentRefusal::none) throw Refusal(std::string("segment refused: ") + fw::motion::to_string(r));
  program_.segments.push_back(segment);
  program_.geometry.push_back(g);
  at_[0] = g.end_mm[0];
  at_[1] = g.end_mm[1];
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
