// Fuzz entry: bytes as an RS274/NGC program through the LinuxCNC-dialect
// interpreter (tools/gcode/canon_interpreter.hpp) with a small tool table
// and .var parameters. Invariants: a refused program returns no call and
// names a line within the text (or 1 for the whole program) and a column
// >= 1; an accepted one starts with the start-up calls, ends (M2,
// M30 or '%') and prints no call with a non-finite number.
#include <string>
#include <string_view>

#include "tests/fuzz/fuzz_entries.hpp"
#include "tools/gcode/canon_interpreter.hpp"

namespace tnv::fuzz {

std::string gcode_canon(const std::uint8_t* data, std::size_t size) {
  static const gcode::CanonSetup setup = [] {
    gcode::CanonSetup s;
    std::string error;
    s.tools.load_text("T1 P1 Z10 D6\nT2 P2 Z-2.5 D3\nT3 P3 Z0.5\n", error);
    s.parameters.load_var_text("5221 1\n5242 -2\n5161 5\n5183 -10\n", error);
    s.max_lines_run = 20'000;  // loops end as errors well inside libFuzzer's timeout
    return s;
  }();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const gcode::CanonResult r = gcode::interpret_canon(text, setup);
  if (r.error) {
    if (!r.calls.empty()) return "a refused program returned calls";
    std::size_t lines = 1;
    for (char c : text) lines += c == '\n';
    if (r.error->line < 1 || static_cast<std::size_t>(r.error->line) > lines) return "error line outside the text";
    if (r.error->column < 1) return "error column < 1";
    if (r.error->message.empty()) return "error without a message";
    return "";
  }
  if (r.calls.size() < 7 || r.calls[5].text != "ON_RESET()") return "accepted program without the start-up calls";
  const std::string& last = r.calls.back().text;
  if (last != "PROGRAM_END()" && last != "FINISH()") return "accepted program that did not end: " + last;
  for (const gcode::CanonCall& c : r.calls) {
    if (c.text.rfind("COMMENT(", 0) == 0 || c.text.rfind("MESSAGE(", 0) == 0 || c.text.rfind("LOG", 0) == 0)
      continue;  // the program's own text (LOG, LOGOPEN, LOGAPPEND: "(LOG,info)" is no number)
    if (c.text.find("nan") != std::string::npos || c.text.find("inf") != std::string::npos)
      return "a call with a non-finite number: " + c.text;
  }
  return "";
}

}  // namespace tnv::fuzz
