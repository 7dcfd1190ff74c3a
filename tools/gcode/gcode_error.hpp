#pragma once
// Where and why a G-code program was refused (host side).
#include <string>

namespace tnv::gcode {

struct GcodeError {
  int line = 0;    // 1-based; 0: the file itself (it could not be read)
  int column = 0;  // 1-based, the word (or character) at fault; 0: the whole line
  std::string message;
  std::string file{};  // set: the line is in this subroutine file, not in the program
};

// "[file, ]line L, column C: why" ("line L: why" without a column).
std::string to_string(const GcodeError& error);

}  // namespace tnv::gcode
