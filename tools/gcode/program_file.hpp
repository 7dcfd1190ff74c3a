#pragma once
// Reading a G-code program file (host side).
#include <cstddef>
#include <string>

namespace tnv::gcode {

// 256 MiB: a CAM post's 3-D surfacing program runs to millions of lines (a
// million moves is about 30 MB). The interpreter holds the program's text
// and 16 bytes a line, not its calls (they stream out as they are made):
// `tnvctl gcode canon` peaks at about 1.7 times the file's size plus 20 MB
// (69 MiB for 30 MB; docs/gcode.md "Speed against rs274"). A machine run
// also holds its segments, 208 bytes a move.
inline constexpr std::size_t kMaxProgramBytes = std::size_t{256} << 20;
// A program file: a regular file of at most kMaxProgramBytes (a FIFO,
// device or directory is refused, never waited on). False with `error`
// set ("<path>: <why>").
bool read_program_file(const std::string& path, std::string& text, std::string& error);

}  // namespace tnv::gcode
