#pragma once
// A parsed program as the SEGMENT / SEGMENT_TAIL frames that carry it
// (firmware/can/segment_wire.hpp), element by element, from where the node
// stands. What one element cannot carry is split exactly: a full circle or
// an arc whose centre lies far off its chord's bisector goes as two halves
// of the same arc, a dwell beyond 838 s as several dwells. Every element
// keeps its G-code line for progress and error messages. A tool change (M6)
// goes as SEGMENT kind tool_change with its tool, so the node knows it once
// the operator continues.
#include <optional>
#include <string>
#include <vector>

#include "firmware/can/segment_wire.hpp"
#include "tools/gcode/gcode_program.hpp"

namespace tnv::can_host {

struct WireElement {
  fw::motion::Segment segment;    // as the node will run it (end points as sent)
  fw::can::SegmentFrames frames;  // tag byte 0: the streamer writes each request's tag
  int line = 0;                   // source line of the G-code (the parsed segment's tag)
  double length_mm = 0.0;         // path length of this element (0 for a dwell)
  std::optional<gcode::ProgramPause> pause;  // a program pause: why (its segment index is the parsed program's)
};

struct WireProgram {
  std::vector<WireElement> elements;
  double length_mm = 0.0;  // sum of the elements' lengths
};

// nullopt with a one-line `error` naming the G-code line when a value does
// not fit the wire (a feed above 655.35 mm/s, an end point beyond +-838 mm).
// `program` must have been parsed from `start_mm` (its first element starts there).
std::optional<WireProgram> wire_program(const gcode::GcodeProgram& program, const fw::motion::PlanePoint& start_mm,
                                        std::uint8_t node, std::string& error);

// The program's segments from index `from` on appended to `out`, from
// `at_mm` (where the node's queue ends; moved to the new end). A program
// read while it runs (it probes) is sent in parts: after a probe the next
// part starts where the node rests. False with `error` as wire_program's;
// `out` then holds the elements before the one that did not fit.
bool wire_append(const gcode::GcodeProgram& program, std::size_t from, fw::motion::PlanePoint& at_mm,
                 std::uint8_t node, WireProgram& out, std::string& error);

// Progress along the program after `elements_done` whole elements: 0..1 of its length.
double length_fraction(const WireProgram& program, std::size_t elements_done);

}  // namespace tnv::can_host
