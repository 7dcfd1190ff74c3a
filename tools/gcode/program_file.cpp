#include "tools/gcode/program_file.hpp"

#include "drivers/storage/regular_file.hpp"

namespace tnv::gcode {

bool read_program_file(const std::string& path, std::string& text, std::string& error) {
  return drivers::read_regular_file(path, kMaxProgramBytes, drivers::LinkPolicy::follow, text, error);
}

}  // namespace tnv::gcode
