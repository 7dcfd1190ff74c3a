#pragma once
// Reading a G-code program file (host side).
#include <cstddef>
#include <string>

namespace tnv::gcode {

// 64 MiB: a CAM post's 3-D surfacing program runs to millions of lines (a
// million moves is about 30 MB). The whole program and its calls are held
// in memory, about 28 times the file's size for `tnvctl gcode canon`
// (180 MB for 6.5 MB of 300 000 moves; 22 times before the calls carried
// their structured form, CanonMotion).
inline constexpr std::size_t kMaxProgramBytes = std::size_t{64} << 20;
// A program file: a regular file of at most kMaxProgramBytes (a FIFO,
// device or directory is refused, never waited on). False with `error`
// set ("<path>: <why>").
bool read_program_file(const std::string& path, std::string& text, std::string& error);

}  // namespace tnv::gcode
