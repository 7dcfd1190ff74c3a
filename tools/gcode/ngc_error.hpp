#pragma once
// The error every stage of the RS274/NGC interpreter (ngc_*) throws on the
// host side: a message and the 1-based column of the word at fault; the
// interpreter adds the line and stops, with nothing emitted.
#include <stdexcept>
#include <string>

namespace tnv::gcode {

class NgcError : public std::runtime_error {
 public:
  NgcError(int column, const std::string& message) : std::runtime_error(message), column_(column) {}
  int column() const noexcept { return column_; }

 private:
  int column_;
};

}  // namespace tnv::gcode
