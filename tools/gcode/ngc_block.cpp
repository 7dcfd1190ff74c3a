#include "tools/gcode/ngc_block.hpp"

#include <cctype>
#include <cmath>
#include <string_view>

#include "tools/gcode/ngc_error.hpp"
#include "tools/gcode/ngc_expression.hpp"

namespace tnv::gcode {

namespace {

// Past a block delete and a line number.
std::size_t skip_prefix(const NgcLine& line, std::size_t pos) {
  const std::string& t = line.text;
  if (pos < t.size() && t[pos] == '/') ++pos;
  if (pos < t.size() && t[pos] == 'n') {
    std::size_t end = pos + 1;
    while (end < t.size() && (std::isdigit(static_cast<unsigned char>(t[end])) || t[end] == '.')) ++end;
    if (end == pos + 1) throw NgcError(line.column_at(pos), "line number N without digits");
    pos = end;
  }
  return pos;
}

struct KeywordName {
  std::string_view text;
  OKeyword keyword;
};
constexpr KeywordName kKeywords[] = {
    {"endsub", OKeyword::endsub},     {"endif", OKeyword::endif},       {"endwhile", OKeyword::endwhile},
    {"endrepeat", OKeyword::endrepeat}, {"elseif", OKeyword::elseif},   {"else", OKeyword::else_},
    {"sub", OKeyword::sub},           {"call", OKeyword::call},         {"return", OKeyword::ret},
    {"if", OKeyword::if_},            {"do", OKeyword::do_},            {"while", OKeyword::while_},
    {"repeat", OKeyword::repeat},     {"break", OKeyword::break_},      {"continue", OKeyword::continue_}};

// The O-word's name and keyword; pos left after the keyword.
NgcOWord read_o_head(const NgcLine& line, std::size_t& pos) {
  const std::string& t = line.text;
  NgcOWord o;
  o.column = line.column_at(pos);
  ++pos;  // 'o'
  if (pos < t.size() && t[pos] == '<') {
    const std::size_t close = t.find('>', pos);
    if (close == std::string::npos) throw NgcError(o.column, "O-word name not closed: '>' missing");
    o.name = t.substr(pos + 1, close - pos - 1);
    if (o.name.empty()) throw NgcError(o.column, "O-word without a name");
    pos = close + 1;
  } else {
    std::size_t end = pos;
    while (end < t.size() && std::isdigit(static_cast<unsigned char>(t[end]))) ++end;
    if (end == pos) throw NgcError(o.column, "O-word needs a number or a <name>");
    std::size_t first = pos;
    while (first + 1 < end && t[first] == '0') ++first;  // o0100 is o100
    o.name = t.substr(first, end - first);
    pos = end;
  }
  for (const KeywordName& k : kKeywords) {
    if (t.compare(pos, k.text.size(), k.text) == 0) {
      o.keyword = k.keyword;
      pos += k.text.size();
      return o;
    }
  }
  throw NgcError(line.column_at(pos), "O-word o" + o.name + " without a known keyword (sub, call, if, while, ...)");
}

// A comment's text from '(' at pos; pos after ')'.
std::string read_comment(const NgcLine& line, std::size_t& pos) {
  const std::string& t = line.text;
  const std::size_t close = t.find(')', pos);
  if (close == std::string::npos) throw NgcError(line.column_at(pos), "comment not closed: ')' missing");
  const std::size_t nested = t.find('(', pos + 1);
  if (nested < close) throw NgcError(line.column_at(nested), "nested comment");
  std::string text = t.substr(pos + 1, close - pos - 1);
  pos = close + 1;
  return text;
}

// D is a real: G41.1/G42.1 take a diameter (G41/G42 check it is a whole tool number).
bool integer_letter(char c) { return c == 'h' || c == 'l' || c == 't'; }

}  // namespace

NgcOWord scan_o_word(const NgcLine& line) {
  std::size_t pos = skip_prefix(line, 0);
  if (pos >= line.text.size() || line.text[pos] != 'o') return {};
  return read_o_head(line, pos);
}

NgcBlock read_block(const NgcLine& line, const NgcParameters& params) {
  const std::string& t = line.text;
  NgcBlock block;
  std::size_t pos = 0;
  if (!t.empty() && t[0] == '/') block.block_delete = true;
  pos = skip_prefix(line, pos);
  if (pos < t.size() && t[pos] == 'o') {
    block.o = read_o_head(line, pos);
    while (pos < t.size() && t[pos] != '(' && t[pos] != ';') block.o.args.push_back(read_real_value(line, pos, params));
  }
  while (pos < t.size()) {
    const char c = t[pos];
    const int column = line.column_at(pos);
    if (c == ';') break;
    if (c == '(') {
      block.comments.push_back(read_comment(line, pos));
      continue;
    }
    if (block.o.keyword != OKeyword::none) throw NgcError(column, "only a comment may follow an O-word");
    if (c == '#') {
      const NgcParamRef ref = read_param_ref(line, pos, params);
      if (pos >= t.size() || t[pos] != '=') throw NgcError(line.column_at(pos), "parameter setting needs '='");
      ++pos;
      NgcAssignment a{ref.name, ref.number, read_real_value(line, pos, params), ref.column};
      if (a.name.empty() && (a.number < 1 || a.number >= NgcParameters::kCount))
        throw NgcError(ref.column, "parameter #" + std::to_string(a.number) + " out of range");
      block.assignments.push_back(std::move(a));
      continue;
    }
    if (c == '@' || c == '^') {
      std::optional<double>& slot = c == '@' ? block.polar_radius : block.polar_angle;
      if (slot) throw NgcError(column, std::string("word ") + c + " twice on one line");
      ++pos;
      slot = read_real_value(line, pos, params);
      (c == '@' ? block.polar_radius_column : block.polar_angle_column) = column;
      continue;
    }
    if (!std::isalpha(static_cast<unsigned char>(c)))
      throw NgcError(column, std::string("unexpected character '") + c + "' where a word letter was expected");
    ++pos;
    if (c == 'g') {
      const double v = read_real_value(line, pos, params) * 10.0;
      const double code = std::floor(v + 0.5);
      if (code < 0.0 || code > 9999.0 || std::fabs(v - code) > 1e-3) throw NgcError(column, "G-code value out of range");
      block.g.push_back({static_cast<int>(code), column});
      continue;
    }
    if (c == 'm') {
      const int code = read_integer_value(line, pos, params);
      if (code < 0 || code > 199) throw NgcError(column, "M-code M" + std::to_string(code) + " out of range");
      block.m.push_back({code, column});
      continue;
    }
    if (c == 'n') throw NgcError(column, "line number N only at the start of a line");
    if (c == 'o') throw NgcError(column, "O-word only at the start of a line");
    if (c == 'e') throw NgcError(column, "unsupported word E");
    const auto k = static_cast<std::size_t>(c - 'a');
    if (block.words[k]) throw NgcError(column, std::string("word ") + static_cast<char>(std::toupper(c)) + " twice on one line");
    block.words[k] = integer_letter(c) ? static_cast<double>(read_integer_value(line, pos, params))
                                       : read_real_value(line, pos, params);
    block.columns[k] = column;
  }
  return block;
}

}  // namespace tnv::gcode
