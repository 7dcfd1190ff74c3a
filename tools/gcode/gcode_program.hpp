#pragma once
// RS274/NGC subset reader for the motion queue (host side): G0 G1 G2 G3
// (I/J and R forms) G4 G17 G20 G21 G90 G91, F, M2 M30, comments ( ) and ;,
// line numbers N and modal state. Every segment is checked against the
// firmware's limits exactly as the queue will check it, so a program that
// parses is a program the queue accepts; an error names line and column and
// no segment is returned.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "firmware/motion/motion_limits.hpp"
#include "firmware/motion/segment.hpp"
#include "firmware/motion/segment_geometry.hpp"

namespace tnv::gcode {

using fw::motion::PlanePoint;

struct GcodeOptions {
  PlanePoint start_mm{0.0, 0.0};   // where the table is when the program starts
  double rapid_feed_mm_s = 50.0;   // G0 path speed
  fw::motion::MotionLimits limits{};
};

struct GcodeError {
  int line = 0;    // 1-based
  int column = 0;  // 1-based, the word (or character) at fault
  std::string message;
  std::string file{};  // set: the line is in this subroutine file, not in the program
};

struct GcodeProgram {
  std::vector<fw::motion::Segment> segments;           // tag = source line
  std::vector<fw::motion::SegmentGeometry> geometry;   // one per segment, with its start point
  bool ended = false;                                  // M2 or M30 seen
  double programmed_length_mm() const noexcept;
  // Sum of length / feed over the feed moves (G1 G2 G3); dwells add their time.
  double programmed_time_s() const noexcept;
};

struct GcodeResult {
  GcodeProgram program;
  std::optional<GcodeError> error;  // set: program is empty
};

GcodeResult parse_gcode(std::string_view text, const GcodeOptions& options = {});
// A program file: a regular file of at most kMaxProgramBytes (a FIFO,
// device or directory is refused, never waited on). False with `error`
// set ("<path>: <why>").
// 64 MiB: a CAM post's 3-D surfacing program runs to millions of lines (a
// million moves is about 30 MB). The whole program and its calls are held
// in memory, about 16 times the file's size for `tnvctl gcode canon`.
inline constexpr std::size_t kMaxProgramBytes = std::size_t{64} << 20;
bool read_program_file(const std::string& path, std::string& text, std::string& error);
GcodeResult parse_gcode_file(const std::string& path, const GcodeOptions& options = {});

std::string to_string(const GcodeError& error);

}  // namespace tnv::gcode
