#pragma once
// One RS274/NGC line as LinuxCNC reads it: blanks outside comments dropped
// and letters lower-cased (so "X 1 0" is X10), each kept character
// remembering its column in the source line for error messages.
#include <string>
#include <string_view>
#include <vector>

namespace tnv::gcode {

struct NgcLine {
  std::string text;          // normalized: no blanks outside comments, lower case outside comments
  std::vector<int> columns;  // source column (1-based) of each character of text
  int column_at(std::size_t i) const noexcept {
    return i < columns.size() ? columns[i] : (columns.empty() ? 1 : columns.back() + 1);
  }
};

// Throws NgcError for a character LinuxCNC refuses outside a comment
// (a control character other than tab and carriage return).
NgcLine normalize_line(std::string_view raw);

// A whole text, one NgcLine per '\n'-separated line (the last one after the
// final newline too). `line_number` is the 1-based line being normalized,
// so a thrown NgcError can be reported at it.
std::vector<NgcLine> normalize_lines(std::string_view text, int& line_number);

}  // namespace tnv::gcode
