#include "tools/gcode/gcode_error.hpp"

namespace tnv::gcode {

std::string to_string(const GcodeError& error) {
  return (error.file.empty() ? "" : error.file + ", ") + "line " + std::to_string(error.line) +
         (error.column > 0 ? ", column " + std::to_string(error.column) : std::string()) + ": " + error.message;
}

}  // namespace tnv::gcode
