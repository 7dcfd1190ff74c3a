#pragma once
// The O-word control flow of a program (LinuxCNC's sub/endsub/call/return,
// if/elseif/else/endif, while/endwhile, do/while, repeat/endrepeat,
// break/continue): which line runs next. O-words pair by name, as in
// LinuxCNC, not by nesting.
#include <array>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tools/gcode/ngc_block.hpp"

namespace tnv::gcode {

class ProgramFlow {
 public:
  static constexpr int kMaxCallDepth = 64;
  // `o_words`: the lines of the program (line_count long) that have an
  // O-word, in order (o_word_lines). A loop that never ends is an error
  // after max_lines_run lines, not a hang.
  ProgramFlow(std::vector<std::pair<std::size_t, NgcOWord>> o_words, std::size_t line_count,
              std::size_t max_lines_run);
  // The next line to run (0-based), nullopt at the end of the file.
  std::optional<std::size_t> next_line();
  // The O-word of the line next_line() returned; throws NgcError.
  void execute(const NgcOWord& o, NgcParameters& params);
  bool in_subroutine() const { return !frames_.empty(); }
  std::size_t depth() const { return frames_.size(); }  // 0 at the top level
  // The subroutine definition (o<name> sub .. endsub, both lines included)
  // that holds `line` (0-based), if one does.
  struct Definition {
    std::string name;
    std::size_t sub = 0, endsub = 0;
  };
  std::optional<Definition> definition_holding(std::size_t line) const;

 private:
  struct Frame {
    std::size_t return_to = 0;
    std::array<double, 30> saved{};  // #1..#30 of the caller
  };
  std::size_t find_forward(std::size_t from, const std::string& name, std::initializer_list<OKeyword> keywords,
                           int column, const char* what) const;
  std::size_t find_backward(std::size_t from, const std::string& name, OKeyword keyword, int column,
                            const char* what) const;
  bool closes_do(std::size_t while_line) const;
  std::size_t loop_end(std::size_t from, const std::string& name, int column) const;

  // Only the lines with an O-word are held (a program of a million moves
  // has a handful): o_at() finds a line's by binary search.
  struct OLine {
    std::size_t line = 0;
    NgcOWord o;
    std::size_t first_opening = 0;  // where its label first opened a block (its own line if it did)
  };
  const NgcOWord& o_at(std::size_t line) const;
  // The first of o_lines_ at or after `line`.
  std::size_t o_index_from(std::size_t line) const;

  std::vector<OLine> o_lines_;
  std::size_t line_count_ = 0;
  std::size_t pc_ = 0;       // the next line
  std::size_t current_ = 0;  // the line being run
  std::size_t lines_run_ = 0;
  std::size_t max_lines_run_;
  std::optional<std::size_t> branch_target_;  // elseif/else reached by a jump from its if
  std::vector<Frame> frames_;
  std::map<std::pair<std::size_t, std::size_t>, long> repeats_left_;  // (frame depth, repeat line) -> count
};

}  // namespace tnv::gcode
