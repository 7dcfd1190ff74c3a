#pragma once
// LinuxCNC's real values on a normalized line (ngc_line.hpp): numbers,
// [expressions] with its operators and precedence (** ; * / mod ; + - ;
// eq ne gt ge lt le ; and or xor), unary functions (abs acos asin atan[y]/[x]
// cos exp fix fup ln round sin sqrt tan exists), parameters #n, ##n, #[..],
// #<name>. Angles are degrees. Errors throw NgcError at the column at fault.
#include <cstddef>
#include <string>

#include "tools/gcode/ngc_line.hpp"
#include "tools/gcode/ngc_parameters.hpp"

namespace tnv::gcode {

// Reads one real value at line.text[pos], advancing pos.
double read_real_value(const NgcLine& line, std::size_t& pos, const NgcParameters& params);
// A real value that must be within 1e-4 of an integer (LinuxCNC's read_integer_value).
int read_integer_value(const NgcLine& line, std::size_t& pos, const NgcParameters& params);
// After '#' at pos: the parameter's reference. Numbered: name empty, number set.
struct NgcParamRef {
  std::string name;
  int number = 0;
  int column = 0;
};
NgcParamRef read_param_ref(const NgcLine& line, std::size_t& pos, const NgcParameters& params);

}  // namespace tnv::gcode
