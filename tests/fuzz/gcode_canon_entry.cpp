// Fuzz entry: bytes as an RS274/NGC program through the LinuxCNC-dialect
// interpreter (tools/gcode/canon_interpreter.hpp) with a small tool table
// and .var parameters. Invariants: a refused program returns no call and
// names a line within the text (or 1 for the whole program) and a column
// >= 1; an accepted one starts with the start-up calls, ends (M2,
// M30 or '%') and prints no call with a non-finite number, in its text or
// its structured form; this XY table's segments of it (canon_segments.hpp)
// are either refused with a message and none returned, or one geometry per
// segment; run from a line the input picks, it is refused on that line or
// ends as the full run.
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "tests/fuzz/fuzz_entries.hpp"
#include "tools/gcode/canon_interpreter.hpp"
#include "tools/gcode/canon_segments.hpp"

namespace tnv::fuzz {

namespace {

std::size_t lines_of(std::string_view text) {
  std::size_t lines = 1;
  for (char c : text) lines += c == '\n';
  return lines;
}

// Run from a line the input picks (docs/gcode.md "Run from line"): refused
// with no call and the error on that line (or on the line that needs a
// skipped probe's result), or the run ends as the full run
// does, after the start-up calls and the comment that marks the start.
std::string run_from_a_line(std::string_view text, const std::vector<gcode::CanonCall>& full, std::size_t lines) {
  gcode::CanonSetup setup;
  std::string error;
  setup.tools.load_text("T1 P1 Z10 D6\nT2 P2 Z-2.5 D3\nT3 P3 Z0.5\n", error);
  setup.parameters.load_var_text("5221 1\n5242 -2\n5161 5\n5183 -10\n", error);
  setup.max_lines_run = 20'000;
  setup.from_line = gcode::RunFromLine{};
  setup.from_line->line = static_cast<int>(1 + text.size() % lines);
  const gcode::CanonResult r = gcode::interpret_canon(text, setup);
  if (r.error) {
    if (!r.calls.empty()) return "a refused start returned calls";
    // Another line only where what the line needs comes from a probe the
    // run skips (docs/gcode.md "Run from line"): the message says so.
    const bool skipped_probe = r.error->message.find("which the run") != std::string::npos &&
                               r.error->message.find("skips; start at or before line ") != std::string::npos;
    if (r.error->line != setup.from_line->line && !skipped_probe) return "a refused start names another line";
    return "";
  }
  if (r.calls.size() < 8 || r.calls[6].text.rfind("COMMENT(\"interpreter: run from line", 0) != 0)
    return "a start without the start-up calls and its comment";
  if (r.calls.back().text != full.back().text || r.calls.size() > full.size() + 40)
    return "a start that does not end as the full run";
  return "";
}

}  // namespace

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
    const std::size_t lines = lines_of(text);
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
  for (const gcode::CanonCall& c : r.calls) {
    const gcode::CanonMotion& m = c.motion;
    bool finite = std::isfinite(m.value);
    for (std::size_t a = 0; a < 3; ++a) finite = finite && std::isfinite(m.end_mm[a]) && std::isfinite(m.centre_mm[a]);
    if (!finite) return "a call with a non-finite number in its structured form: " + c.text;
  }
  const gcode::GcodeResult machine = gcode::canon_segments(r, setup.start_machine_mm, gcode::GcodeOptions{});
  if (machine.error && (machine.error->message.empty() || !machine.program.segments.empty()))
    return "a refusal of the segments without a message, or with segments";
  if (machine.program.segments.size() != machine.program.geometry.size()) return "a segment without its geometry";
  return run_from_a_line(text, r.calls, lines_of(text));
}

}  // namespace tnv::fuzz
