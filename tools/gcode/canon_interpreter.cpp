#include "tools/gcode/canon_interpreter.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>

#include "tools/gcode/canon_state.hpp"
#include "tools/gcode/ngc_block.hpp"
#include "tools/gcode/ngc_error.hpp"
#include "tools/gcode/ngc_program_flow.hpp"
#include "tools/gcode/ngc_program_lines.hpp"
#include "tools/gcode/ngc_subroutine_files.hpp"
#include "tools/gcode/program_file.hpp"

namespace tnv::gcode {

namespace {

std::string label(const std::string& name) {
  const bool number = !name.empty() && name.find_first_not_of("0123456789") == std::string::npos;
  return number ? "o" + name : "o<" + name + ">";
}

// Refusals known before anything runs; `line_number` is where the error is reported.
void check_start_line(const RunFromLine& from, std::size_t line_count, const ProgramFlow& flow, int& line_number) {
  line_number = from.line;
  const std::string at = "cannot run from line " + std::to_string(from.line) + ": ";
  if (from.line < 1 || static_cast<std::size_t>(from.line) > line_count)
    throw NgcError(1, at + "the program has lines 1 to " + std::to_string(line_count));
  if (from.pass < 1) throw NgcError(1, at + "the pass must be 1 or more");
  if (!std::isfinite(from.clearance_z_mm) || !std::isfinite(from.approach_mm) || from.approach_mm < 0.0)
    throw NgcError(1, at + "the clearance must be a number and the approach height a number >= 0");
  for (double v : from.machine_position_mm)
    if (!std::isfinite(v)) throw NgcError(1, at + "the machine position must be numbers");
  if (from.tool_in_spindle < 0) throw NgcError(1, at + "negative tool number in the spindle");
  if (const auto def = flow.definition_holding(static_cast<std::size_t>(from.line - 1)))
    throw NgcError(1, at + "it is in the definition of subroutine " + label(def->name) + " (lines " +
                          std::to_string(def->sub + 1) + " to " + std::to_string(def->endsub + 1) +
                          "), which runs only when called; start at the line that calls it");
}

}  // namespace

CanonRun interpret_canon_to(std::string_view text, const CanonSetup& setup, const CanonSink& sink) {
  CanonRun result;
  CanonMachine machine(setup, sink);
  int line_number = 0;
  std::string line_file;  // set while a line of a subroutine file runs
  try {
    ProgramLines lines(text, line_number);
    const std::size_t program_lines = lines.size();
    std::size_t calling_line = 0;
    SubroutineFiles files;
    try {
      files = append_subroutine_files(lines, setup.subroutine_path, calling_line);
    } catch (const NgcError&) {
      line_number = static_cast<int>(calling_line);  // the program's line (files load before anything runs)
      throw;
    }
    // Where line `index` (0-based, in `lines`) comes from: the program, or a subroutine file.
    const auto locate = [&](std::size_t index) {
      if (index < program_lines) {
        line_file.clear();
        line_number = static_cast<int>(index) + 1;
        machine.set_file(0);
      } else {
        const SubroutineFiles::Origin& o = files.origins[index - program_lines];
        line_file = files.files[o.file];
        line_number = o.line;
        machine.set_file(static_cast<std::uint32_t>(o.file) + 1);
      }
    };
    ProgramFlow flow(o_word_lines(lines), lines.size(), setup.max_lines_run);
    long passes_left = 0;
    if (setup.from_line) {
      check_start_line(*setup.from_line, program_lines, flow, line_number);
      passes_left = setup.from_line->pass;
    }
    for (double v : setup.start_machine_mm)
      if (!std::isfinite(v)) throw NgcError(1, "the start position must be numbers");
    machine.start();
    if (setup.from_line) machine.mute();
    while (!machine.ended()) {
      const std::optional<std::size_t> next = flow.next_line();
      if (!next) break;
      locate(*next);
      if (machine.muted() && line_file.empty() && line_number == setup.from_line->line && --passes_left == 0)
        machine.resume(*setup.from_line, line_number);
      if (!machine.muted()) ++result.lines_run;
      const NgcLine line = lines.line(*next);
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
    if (!machine.ended()) {
      locate(program_lines - 1);  // the program's own end, not a file's
      if (setup.end_of_file_ends) machine.end_at_end_of_file(line_number);
      else machine.end_of_file(line_number);
    }
    result.files = files.files;
    if (machine.muted()) {
      const RunFromLine& from = *setup.from_line;
      const long runs = from.pass - passes_left;
      line_number = from.line;
      throw NgcError(1, "cannot run from line " + std::to_string(from.line) + ": " +
                            (runs == 0 ? std::string("the program never runs it (it ends first, or the line is in a "
                                                     "branch or loop that does not run)")
                                       : "it runs only " + std::to_string(runs) + " time" + (runs == 1 ? "" : "s") +
                                             ", not " + std::to_string(from.pass)));
    }
  } catch (const NgcError& e) {
    result.files.clear();
    result.lines_run = 0;
    result.error = GcodeError{line_number, e.column(), e.what(), line_file};
  }
  return result;
}

CanonResult interpret_canon(std::string_view text, const CanonSetup& setup) {
  CanonResult result;
  static_cast<CanonRun&>(result) =
      interpret_canon_to(text, setup, [&result](const CanonCall& call) { result.calls.push_back(call); });
  if (result.error) result.calls.clear();
  return result;
}

std::string canon_text(const std::vector<CanonCall>& calls) {
  std::string out;
  for (const CanonCall& c : calls) out.append(c.text).push_back('\n');
  return out;
}

CanonRun interpret_canon_file_to(const std::string& path, const CanonSetup& setup, const CanonSink& sink) {
  std::string text;
  std::string error;
  if (!read_program_file(path, text, error)) {
    CanonRun r;
    r.error = GcodeError{0, 0, error};
    return r;
  }
  CanonSetup with_own_directory = setup;
  add_program_directory(with_own_directory, path);
  return interpret_canon_to(text, with_own_directory, sink);
}

CanonResult interpret_canon_file(const std::string& path, const CanonSetup& setup) {
  CanonResult result;
  static_cast<CanonRun&>(result) =
      interpret_canon_file_to(path, setup, [&result](const CanonCall& call) { result.calls.push_back(call); });
  if (result.error) result.calls.clear();
  return result;
}

void add_program_directory(CanonSetup& setup, const std::string& program_path) {
  const std::filesystem::path dir = std::filesystem::path(program_path).parent_path();
  setup.subroutine_path.insert(setup.subroutine_path.begin(), dir.empty() ? std::string(".") : dir.string());
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
