#include "tools/gcode/canon_interpreter.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include "tools/gcode/canon_state.hpp"
#include "tools/gcode/ngc_block.hpp"
#include "tools/gcode/ngc_error.hpp"
#include "tools/gcode/ngc_program_flow.hpp"

namespace tnv::gcode {

CanonResult interpret_canon(std::string_view text, const CanonSetup& setup) {
  CanonResult result;
  CanonMachine machine(setup, result.calls);
  std::string why;
  std::vector<NgcLine> lines;
  int line_number = 0;
  try {
    std::size_t pos = 0;
    while (pos <= text.size()) {
      std::size_t eol = text.find('\n', pos);
      if (eol == std::string_view::npos) eol = text.size();
      ++line_number;
      lines.push_back(normalize_line(text.substr(pos, eol - pos)));
      pos = eol + 1;
    }
    ProgramFlow flow(lines, setup.max_lines_run);
    machine.start();
    while (!machine.ended()) {
      const std::optional<std::size_t> next = flow.next_line();
      if (!next) break;
      line_number = static_cast<int>(*next) + 1;
      const NgcLine& line = lines[*next];
      if (line.text.empty()) continue;
      if (setup.block_delete && line.text[0] == '/') continue;
      if (line.text[0] == '%') {
        if (line.text.size() > 1 && line.text[1] != ';' && line.text[1] != '(')
          throw NgcError(line.column_at(1), "only a comment may follow '%'");
        machine.percent(line_number, line.column_at(0));
        continue;
      }
      machine.begin_line(line_number);
      const NgcBlock block = read_block(line, machine.parameters());
      if (block.o.keyword != OKeyword::none) {
        flow.execute(block.o, machine.parameters());
        machine.set_call_depth(flow.depth(), line_number);
        machine.comments(block, line_number);
        continue;
      }
      machine.execute(block, line_number);
    }
    if (!machine.ended()) machine.end_of_file(line_number);
  } catch (const NgcError& e) {
    result.calls.clear();
    result.error = GcodeError{line_number, e.column(), e.what()};
  }
  return result;
}

std::string canon_text(const std::vector<CanonCall>& calls) {
  std::string out;
  for (const CanonCall& c : calls) out.append(c.text).push_back('\n');
  return out;
}

CanonResult interpret_canon_file(const std::string& path, const CanonSetup& setup) {
  std::string text;
  std::string error;
  if (!read_program_file(path, text, error)) {
    CanonResult r;
    r.error = GcodeError{0, 0, error};
    return r;
  }
  return interpret_canon(text, setup);
}

namespace {

constexpr std::size_t kMaxTableBytes = 4u << 20;

bool read_small_file(const std::string& path, std::string& text, std::string& error) {
  return read_program_file(path, text, error) && (text.size() <= kMaxTableBytes || (error = path + ": too large", false));
}

}  // namespace

bool load_tool_table_file(const std::string& path, CanonSetup& setup, std::string& error) {
  std::string text;
  if (!read_small_file(path, text, error)) return false;
  if (!setup.tools.load_text(text, error)) {
    error = path + ": " + error;
    return false;
  }
  return true;
}

bool load_var_file(const std::string& path, CanonSetup& setup, std::string& error) {
  std::string text;
  if (!read_small_file(path, text, error)) return false;
  if (!setup.parameters.load_var_text(text, error)) {
    error = path + ": " + error;
    return false;
  }
  return true;
}

}  // namespace tnv::gcode
