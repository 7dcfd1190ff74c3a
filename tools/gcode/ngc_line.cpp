#include "tools/gcode/ngc_line.hpp"

#include <cctype>

#include "tools/gcode/ngc_error.hpp"

namespace tnv::gcode {

NgcLine normalize_line(std::string_view raw) {
  NgcLine out;
  out.text.reserve(raw.size());
  out.columns.reserve(raw.size());
  bool in_comment = false;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const auto c = static_cast<unsigned char>(raw[i]);
    const int column = static_cast<int>(i) + 1;
    if (in_comment) {
      out.text.push_back(static_cast<char>(c));
      out.columns.push_back(column);
      if (c == ')') in_comment = false;
      continue;
    }
    if (c == ';') {  // the rest of the line is a comment, kept verbatim
      out.text.append(raw.substr(i));
      for (std::size_t k = i; k < raw.size(); ++k) out.columns.push_back(static_cast<int>(k) + 1);
      break;
    }
    if (c == ' ' || c == '\t' || c == '\r') continue;
    if (c < 32 || c == 127) throw NgcError(column, "control character (code " + std::to_string(c) + ") in the line");
    if (c == '(') in_comment = true;
    out.text.push_back(static_cast<char>(std::tolower(c)));
    out.columns.push_back(column);
  }
  return out;
}

std::vector<NgcLine> normalize_lines(std::string_view text, int& line_number) {
  std::vector<NgcLine> lines;
  line_number = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    ++line_number;
    lines.push_back(normalize_line(text.substr(pos, eol - pos)));
    pos = eol + 1;
  }
  return lines;
}

}  // namespace tnv::gcode
