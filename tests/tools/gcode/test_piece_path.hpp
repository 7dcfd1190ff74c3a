#pragma once
#include <string>

namespace tnv::gcode::test {

// A file of tests/data/paths/. Appended piece by piece: GCC 12 warns
// falsely (-Warray-bounds) on a chain of string + in unity builds.
inline std::string test_piece_path(const char* name) {
  std::string path = TNV_SOURCE_DIR;
  path += "/tests/data/paths/";
  path += name;
  return path;
}

}  // namespace tnv::gcode::test
