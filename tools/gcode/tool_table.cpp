#include "tools/gcode/tool_table.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>

namespace tnv::gcode {

bool ToolTable::load_text(const std::string& text, std::string& error) {
  std::map<int, ToolEntry> loaded;
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  int index = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const std::size_t semicolon = line.find(';');
    if (semicolon != std::string::npos) line.resize(semicolon);
    std::istringstream fields(line);
    std::string field;
    ToolEntry e;
    bool has_tool = false, any = false;
    const auto fail = [&](const std::string& why) {
      error = "line " + std::to_string(line_number) + ": " + why;
      return false;
    };
    while (fields >> field) {
      any = true;
      const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(field[0])));
      double v = 0.0;
      const char* begin = field.data() + 1;
      const char* end = field.data() + field.size();
      if (begin < end && *begin == '+') ++begin;
      const auto r = std::from_chars(begin, end, v);
      if (begin == end || r.ec != std::errc() || r.ptr != end || !std::isfinite(v))
        return fail("'" + field + "' is not a letter and a number");
      static const std::string kAxes = "XYZABCUVW";
      const std::size_t axis = kAxes.find(letter);
      if (axis != std::string::npos) {
        e.offset[axis] = v;
      } else if (letter == 'T' || letter == 'P' || letter == 'Q') {
        if (v != std::floor(v) || v < 0.0 || v > 1e6) return fail("'" + field + "' needs a whole number >= 0");
        (letter == 'T' ? e.tool : letter == 'P' ? e.pocket : e.orientation) = static_cast<int>(v);
        if (letter == 'T') has_tool = true;
      } else if (letter == 'D') {
        e.diameter = v;
      } else if (letter == 'I') {
        e.front_angle = v;
      } else if (letter == 'J') {
        e.back_angle = v;
      } else {
        return fail("unknown field '" + field + "'");
      }
    }
    if (!any) continue;
    if (!has_tool) return fail("a tool line without T<number>");
    if (loaded.count(e.tool) != 0) return fail("tool T" + std::to_string(e.tool) + " twice");
    e.index = ++index;
    loaded[e.tool] = e;
  }
  tools_ = std::move(loaded);
  return true;
}

const ToolEntry* ToolTable::find(int tool) const {
  const auto it = tools_.find(tool);
  return it == tools_.end() ? nullptr : &it->second;
}

void ToolTable::replace(const ToolEntry& entry) {
  const auto it = tools_.find(entry.tool);
  if (it != tools_.end()) it->second = entry;
}

}  // namespace tnv::gcode
