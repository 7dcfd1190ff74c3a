#pragma once
// A program's lines as the interpreter runs them: the raw text of each line
// (a view into the program's text, which the caller keeps, or into a
// subroutine file's text, which this keeps), normalized only when the line
// runs. Held per line: a view (16 bytes), not its normalized copy (a string
// and a column per character, about seven times the line), so a program of
// a million lines costs its text and 16 MB, not hundreds.
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tools/gcode/ngc_block.hpp"
#include "tools/gcode/ngc_line.hpp"

namespace tnv::gcode {

class ProgramLines {
 public:
  // Appends to `out` the lines of `text` ('\n'-separated, the last one
  // after the final newline too), each checked as normalize_line checks it:
  // throws NgcError for a character LinuxCNC refuses, with `line_number`
  // the 1-based line in `text`. The views point into `text`.
  static void split_checked(std::string_view text, int& line_number, std::vector<std::string_view>& out);

  ProgramLines() = default;
  // The program's lines (split_checked); `text` must outlive this.
  ProgramLines(std::string_view text, int& line_number) { split_checked(text, line_number, raw_); }

  void append(std::string_view raw) { raw_.push_back(raw); }
  // Keeps a subroutine file's text for the lines appended from it.
  std::string_view keep(std::string text) {
    owned_.push_back(std::make_unique<std::string>(std::move(text)));
    return *owned_.back();
  }
  std::size_t size() const noexcept { return raw_.size(); }
  std::string_view raw(std::size_t index) const { return raw_[index]; }
  NgcLine line(std::size_t index) const { return normalize_line(raw_[index]); }

 private:
  std::vector<std::string_view> raw_;
  std::vector<std::unique_ptr<std::string>> owned_;
};

// The O-word of a raw line, without evaluating anything (scan_o_word);
// nullopt for a line without one, or one that does not scan (read_block
// reports it when the line runs).
std::optional<NgcOWord> raw_o_word(std::string_view raw);

// Every line of `lines` from `from` on that has an O-word: (index, O-word), in order.
std::vector<std::pair<std::size_t, NgcOWord>> o_word_lines(const ProgramLines& lines, std::size_t from = 0);

}  // namespace tnv::gcode
