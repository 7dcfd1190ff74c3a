#include "tools/gcode/ngc_expression.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>
#include <string_view>
#include <vector>

#include "tools/gcode/ngc_error.hpp"

namespace tnv::gcode {

namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
constexpr double kEqualTolerance = 1e-4;  // LinuxCNC's TOLERANCE_EQUAL for eq/ne

enum class Op { power, times, divide, mod, plus, minus, eq, ne, gt, ge, lt, le, op_and, op_or, op_xor, close };

int precedence(Op op) {
  switch (op) {
    case Op::close: return 1;
    case Op::op_and: case Op::op_or: case Op::op_xor: return 2;
    case Op::eq: case Op::ne: case Op::gt: case Op::ge: case Op::lt: case Op::le: return 3;
    case Op::plus: case Op::minus: return 4;
    case Op::times: case Op::divide: case Op::mod: return 5;
    case Op::power: return 6;
  }
  return 0;
}

bool starts_with(const std::string& text, std::size_t pos, std::string_view word) {
  return text.compare(pos, word.size(), word) == 0;
}

Op read_operation(const NgcLine& line, std::size_t& pos) {
  const std::string& t = line.text;
  const int column = line.column_at(pos);
  if (pos >= t.size()) throw NgcError(column, "expression not closed: ']' missing");
  struct Name { std::string_view text; Op op; };
  static constexpr Name kNames[] = {{"**", Op::power}, {"*", Op::times}, {"/", Op::divide}, {"+", Op::plus},
                                    {"-", Op::minus},  {"]", Op::close}, {"mod", Op::mod},   {"eq", Op::eq},
                                    {"ne", Op::ne},    {"gt", Op::gt},   {"ge", Op::ge},     {"lt", Op::lt},
                                    {"le", Op::le},    {"and", Op::op_and}, {"or", Op::op_or}, {"xor", Op::op_xor}};
  for (const Name& n : kNames) {
    if (starts_with(t, pos, n.text)) {
      pos += n.text.size();
      return n.op;
    }
  }
  throw NgcError(column, std::string("unknown operation at '") + t[pos] + "'");
}

double apply(Op op, double left, double right, int column) {
  switch (op) {
    case Op::power:
      if (left < 0.0 && std::floor(right) != right) throw NgcError(column, "attempt to raise a negative number to a non-integer power");
      return std::pow(left, right);
    case Op::times: return left * right;
    case Op::divide:
      if (right == 0.0) throw NgcError(column, "attempt to divide by zero");
      return left / right;
    case Op::mod: {
      if (right == 0.0) throw NgcError(column, "attempt to divide by zero (mod)");
      double r = std::fmod(left, right);
      if (r < 0.0) r += std::fabs(right);
      return r;
    }
    case Op::plus: return left + right;
    case Op::minus: return left - right;
    case Op::eq: return std::fabs(left - right) < kEqualTolerance ? 1.0 : 0.0;
    case Op::ne: return std::fabs(left - right) >= kEqualTolerance ? 1.0 : 0.0;
    case Op::gt: return left > right ? 1.0 : 0.0;
    case Op::ge: return left >= right ? 1.0 : 0.0;
    case Op::lt: return left < right ? 1.0 : 0.0;
    case Op::le: return left <= right ? 1.0 : 0.0;
    case Op::op_and: return (left == 0.0 || right == 0.0) ? 0.0 : 1.0;
    case Op::op_or: return (left != 0.0 || right != 0.0) ? 1.0 : 0.0;
    case Op::op_xor: return ((left == 0.0) != (right == 0.0)) ? 1.0 : 0.0;
    case Op::close: break;
  }
  return 0.0;
}

constexpr int kMaxDepth = 64;  // nested brackets and functions: a limit, not a stack overflow

double read_expression(const NgcLine& line, std::size_t& pos, const NgcParameters& params, int depth);

double read_value(const NgcLine& line, std::size_t& pos, const NgcParameters& params, int depth);

double read_number(const NgcLine& line, std::size_t& pos) {
  const std::string& t = line.text;
  const int column = line.column_at(pos);
  std::size_t end = pos;
  bool negative = false;
  if (end < t.size() && (t[end] == '+' || t[end] == '-')) {
    negative = t[end] == '-';
    ++end;
  }
  const std::size_t digits_start = end;
  bool any_digit = false, point = false;
  while (end < t.size() && (std::isdigit(static_cast<unsigned char>(t[end])) || (t[end] == '.' && !point))) {
    if (t[end] == '.') point = true;
    else any_digit = true;
    ++end;
  }
  if (!any_digit) throw NgcError(column, "bad number format");
  double value = 0.0;
  std::string digits(t.substr(digits_start, end - digits_start));
  if (digits.back() == '.') digits.pop_back();
  if (digits.front() == '.') digits.insert(digits.begin(), '0');
  const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (r.ec != std::errc() || !std::isfinite(value)) throw NgcError(column, "bad number format");
  pos = end;
  return negative ? -value : value;
}

double read_function(const NgcLine& line, std::size_t& pos, const NgcParameters& params, int depth) {
  const std::string& t = line.text;
  const int column = line.column_at(pos);
  static constexpr std::string_view kNames[] = {"abs", "acos", "asin", "atan", "cos",  "exp",  "exists",
                                                "fix", "fup",  "ln",   "round", "sin", "sqrt", "tan"};
  std::string_view name;
  for (std::string_view n : kNames)
    if (starts_with(t, pos, n) && n.size() > name.size()) name = n;
  if (name.empty()) throw NgcError(column, "unknown word or function where a value was expected");
  pos += name.size();
  if (pos >= t.size() || t[pos] != '[') throw NgcError(line.column_at(pos), "function " + std::string(name) + " needs [ ]");
  if (name == "exists") {
    ++pos;
    if (pos + 1 >= t.size() || t[pos] != '#' || t[pos + 1] != '<')
      throw NgcError(line.column_at(pos), "exists needs a named parameter #<name>");
    const std::size_t close = t.find('>', pos);
    if (close == std::string::npos) throw NgcError(line.column_at(pos), "named parameter not closed: '>' missing");
    const std::string pname = t.substr(pos + 2, close - pos - 2);
    pos = close + 1;
    if (pos >= t.size() || t[pos] != ']') throw NgcError(line.column_at(pos), "exists: ']' missing");
    ++pos;
    return params.exists(pname) ? 1.0 : 0.0;
  }
  const double v = read_expression(line, pos, params, depth + 1);
  if (name == "atan") {
    if (pos >= t.size() || t[pos] != '/') throw NgcError(line.column_at(pos), "atan needs the form atan[y]/[x]");
    ++pos;
    if (pos >= t.size() || t[pos] != '[') throw NgcError(line.column_at(pos), "atan needs the form atan[y]/[x]");
    const double x = read_expression(line, pos, params, depth + 1);
    return std::atan2(v, x) * kDegPerRad;
  }
  if (name == "abs") return std::fabs(v);
  if (name == "acos" || name == "asin") {
    if (v < -1.0 || v > 1.0) throw NgcError(column, std::string(name) + " argument out of range [-1, 1]");
    return (name == "acos" ? std::acos(v) : std::asin(v)) * kDegPerRad;
  }
  if (name == "cos") return std::cos(v / kDegPerRad);
  if (name == "sin") return std::sin(v / kDegPerRad);
  if (name == "tan") return std::tan(v / kDegPerRad);
  if (name == "exp") return std::exp(v);
  if (name == "fix") return std::floor(v);
  if (name == "fup") return std::ceil(v);
  if (name == "ln") {
    if (v <= 0.0) throw NgcError(column, "ln of zero or a negative number");
    return std::log(v);
  }
  if (name == "round") return static_cast<double>(static_cast<long long>(v + (v < 0.0 ? -0.5 : 0.5)));
  if (v < 0.0) throw NgcError(column, "sqrt of a negative number");
  return std::sqrt(v);
}

double read_expression(const NgcLine& line, std::size_t& pos, const NgcParameters& params, int depth) {
  if (depth > kMaxDepth) throw NgcError(line.column_at(pos), "expression nested too deeply");
  ++pos;  // '['
  std::vector<double> values;
  std::vector<std::pair<Op, int>> ops;
  values.push_back(read_value(line, pos, params, depth));
  for (;;) {
    const int column = line.column_at(pos);
    const Op op = read_operation(line, pos);
    while (!ops.empty() && precedence(ops.back().first) >= precedence(op)) {
      const double right = values.back();
      values.pop_back();
      values.back() = apply(ops.back().first, values.back(), right, ops.back().second);
      ops.pop_back();
    }
    if (op == Op::close) break;
    ops.emplace_back(op, column);
    values.push_back(read_value(line, pos, params, depth));
  }
  if (!std::isfinite(values.back())) throw NgcError(line.column_at(pos), "expression result is not a finite number");
  return values.back();
}

double read_value(const NgcLine& line, std::size_t& pos, const NgcParameters& params, int depth) {
  if (depth > kMaxDepth) throw NgcError(line.column_at(pos), "expression nested too deeply");
  const std::string& t = line.text;
  if (pos >= t.size()) throw NgcError(line.column_at(pos), "a value is missing at the end of the line");
  const char c = t[pos];
  if (c == '[') return read_expression(line, pos, params, depth + 1);
  if (c == '#') {
    const NgcParamRef ref = read_param_ref(line, pos, params);
    return ref.name.empty() ? params.get(ref.number, ref.column) : params.get(ref.name, ref.column);
  }
  if ((c == '-' || c == '+') && pos + 1 < t.size() && !std::isdigit(static_cast<unsigned char>(t[pos + 1])) &&
      t[pos + 1] != '.') {
    ++pos;
    const double v = read_value(line, pos, params, depth + 1);
    return c == '-' ? -v : v;
  }
  if (std::isalpha(static_cast<unsigned char>(c))) return read_function(line, pos, params, depth);
  return read_number(line, pos);
}

}  // namespace

NgcParamRef read_param_ref(const NgcLine& line, std::size_t& pos, const NgcParameters& params) {
  const std::string& t = line.text;
  NgcParamRef ref;
  ref.column = line.column_at(pos);
  ++pos;  // '#'
  if (pos < t.size() && t[pos] == '<') {
    const std::size_t close = t.find('>', pos);
    if (close == std::string::npos) throw NgcError(ref.column, "named parameter not closed: '>' missing");
    ref.name = t.substr(pos + 1, close - pos - 1);
    if (ref.name.empty()) throw NgcError(ref.column, "named parameter without a name");
    for (char ch : ref.name)
      if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_')
        throw NgcError(ref.column, "named parameter #<" + ref.name + ">: only letters, digits and _ in a name");
    pos = close + 1;
    return ref;
  }
  ref.number = read_integer_value(line, pos, params);
  return ref;
}

double read_real_value(const NgcLine& line, std::size_t& pos, const NgcParameters& params) {
  return read_value(line, pos, params, 0);
}

int read_integer_value(const NgcLine& line, std::size_t& pos, const NgcParameters& params) {
  const int column = line.column_at(pos);
  const double v = read_real_value(line, pos, params);
  const double rounded = std::floor(v + 0.5);
  if (std::fabs(v - rounded) > 1e-4 || std::fabs(rounded) > 1e9) throw NgcError(column, "non-integer value for integer");
  return static_cast<int>(rounded);
}

}  // namespace tnv::gcode
