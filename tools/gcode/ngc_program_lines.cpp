#include "tools/gcode/ngc_program_lines.hpp"

#include "tools/gcode/ngc_error.hpp"

namespace tnv::gcode {

void ProgramLines::split_checked(std::string_view text, int& line_number, std::vector<std::string_view>& lines) {
  line_number = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    ++line_number;
    const std::string_view raw = text.substr(pos, eol - pos);
    // Only a line with a control character can be refused (outside a
    // comment): normalizing it says whether it is, and where.
    for (const char ch : raw) {
      const auto c = static_cast<unsigned char>(ch);
      if ((c < 32 && c != '\t' && c != '\r') || c == 127) {
        (void)normalize_line(raw);
        break;
      }
    }
    lines.push_back(raw);
    pos = eol + 1;
  }
}

std::optional<NgcOWord> raw_o_word(std::string_view raw) {
  if (raw.find_first_of("oO") == std::string_view::npos) return std::nullopt;  // no O-word without an o
  try {
    NgcOWord o = scan_o_word(normalize_line(raw));
    if (o.keyword != OKeyword::none) return o;
  } catch (const NgcError&) {
    // reported when the line runs
  }
  return std::nullopt;
}

std::vector<std::pair<std::size_t, NgcOWord>> o_word_lines(const ProgramLines& lines, std::size_t from) {
  std::vector<std::pair<std::size_t, NgcOWord>> out;
  for (std::size_t i = from; i < lines.size(); ++i)
    if (std::optional<NgcOWord> o = raw_o_word(lines.raw(i))) out.emplace_back(i, std::move(*o));
  return out;
}

}  // namespace tnv::gcode
