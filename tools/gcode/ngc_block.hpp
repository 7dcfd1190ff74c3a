#pragma once
// One RS274/NGC line read into a block as LinuxCNC reads it: block delete,
// line number, words (G and M codes kept in order, every other letter at
// most once), parameter settings (applied after the line is read), comments
// and messages, or an O-word with its keyword and arguments.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "tools/gcode/ngc_line.hpp"
#include "tools/gcode/ngc_parameters.hpp"

namespace tnv::gcode {

struct NgcCode {
  int code = 0;    // G: value x 10 (G38.2 -> 382); M: the value
  int column = 0;
};

struct NgcAssignment {
  std::string name;  // empty: numbered
  int number = 0;
  double value = 0.0;
  int column = 0;
};

enum class OKeyword { none, sub, endsub, call, ret, if_, elseif, else_, endif, do_, while_, endwhile, repeat,
                      endrepeat, break_, continue_ };

struct NgcOWord {
  OKeyword keyword = OKeyword::none;
  std::string name;      // "100" or "name" (from o<name>)
  int column = 0;
  std::vector<double> args;  // call arguments; if/while/repeat/return/endsub: the one expression, if any
};

struct NgcBlock {
  bool block_delete = false;
  std::vector<NgcCode> g;
  std::vector<NgcCode> m;
  std::array<std::optional<double>, 26> words{};  // every letter but G, M, N, O
  std::array<int, 26> columns{};
  std::optional<double> polar_radius, polar_angle;  // @ and ^ (LinuxCNC's polar coordinates)
  int polar_radius_column = 0, polar_angle_column = 0;
  std::vector<NgcAssignment> assignments;
  std::vector<std::string> comments;  // text inside ( ), in order
  NgcOWord o;
  bool has(char letter) const { return words[static_cast<std::size_t>(letter - 'a')].has_value(); }
  double value(char letter) const { return words[static_cast<std::size_t>(letter - 'a')].value_or(0.0); }
  int column(char letter) const { return columns[static_cast<std::size_t>(letter - 'a')]; }
};

// The O-word of a line without evaluating anything (the control-flow
// scan); keyword none for a line without one.
NgcOWord scan_o_word(const NgcLine& line);

// Reads the whole line, evaluating its values with `params` (which it does
// not change: settings are returned in the block). Throws NgcError.
NgcBlock read_block(const NgcLine& line, const NgcParameters& params);

}  // namespace tnv::gcode
