#include "tools/gcode/ngc_parameters.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

#include "tools/gcode/ngc_error.hpp"

namespace tnv::gcode {

// A subroutine's return value and its flag read 0 before any return, as in LinuxCNC.
NgcParameters::NgcParameters() : globals_{{"_value", 0.0}, {"_value_returned", 0.0}}, locals_(1) {}

double NgcParameters::get(int number, int column) const {
  if (number < 0 || number >= kCount)
    throw NgcError(column, "parameter #" + std::to_string(number) + " out of range (1.." + std::to_string(kCount - 1) + ")");
  if (!unknown_numbers_.empty())
    if (const auto it = unknown_numbers_.find(number); it != unknown_numbers_.end())
      throw NgcError(column, "#" + std::to_string(number) + " " + it->second);
  if (read_only(number)) return machine_ ? machine_->read_only_number(number) : 0.0;
  return numbered_[static_cast<std::size_t>(number)];
}

void NgcParameters::set(int number, double value, int column) {
  if (number < 1 || number >= kCount)
    throw NgcError(column, "parameter #" + std::to_string(number) + " out of range (1.." + std::to_string(kCount - 1) + ")");
  if (read_only(number)) throw NgcError(column, "parameter #" + std::to_string(number) + " is read-only");
  numbered_[static_cast<std::size_t>(number)] = value;
  if (!unknown_numbers_.empty()) unknown_numbers_.erase(number);
}

double NgcParameters::get(const std::string& name, int column) const {
  if (!unknown_names_.empty())
    if (const auto it = unknown_names_.find(name); it != unknown_names_.end())
      throw NgcError(column, "#<" + name + "> " + it->second);
  if (!name.empty() && name[0] == '_') {
    if (machine_)
      if (const std::optional<double> v = machine_->predefined(name)) return *v;
    const auto it = globals_.find(name);
    if (it != globals_.end()) return it->second;
  } else {
    const auto it = locals_.back().find(name);
    if (it != locals_.back().end()) return it->second;
  }
  throw NgcError(column, "named parameter #<" + name + "> not defined");
}

bool NgcParameters::exists(const std::string& name) const {
  if (!name.empty() && name[0] == '_') return globals_.count(name) != 0 || (machine_ && machine_->predefined(name));
  return locals_.back().count(name) != 0;
}

void NgcParameters::set(const std::string& name, double value) {
  if (!name.empty() && name[0] == '_') globals_[name] = value;
  else locals_.back()[name] = value;
}

void NgcParameters::assign(const std::string& name, double value, int column) {
  const bool interpreters_own = name == "_value" || name == "_value_returned";
  if (interpreters_own || (!name.empty() && name[0] == '_' && machine_ && machine_->predefined(name)))
    throw NgcError(column, "cannot assign to read-only parameter #<" + name + ">");
  set(name, value);
}

void NgcParameters::push_scope() { locals_.emplace_back(); }

void NgcParameters::pop_scope() {
  if (locals_.size() > 1) locals_.pop_back();
}

bool NgcParameters::load_var_text(const std::string& text, std::string& error) {
  std::array<double, kCount> loaded = numbered_;
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    std::istringstream fields(line);
    std::string number_text, value_text;
    if (!(fields >> number_text)) continue;  // blank line
    if (!(fields >> value_text)) {
      error = "line " + std::to_string(line_number) + ": a parameter number without a value";
      return false;
    }
    int number = 0;
    double value = 0.0;
    const auto n = std::from_chars(number_text.data(), number_text.data() + number_text.size(), number);
    const auto v = std::from_chars(value_text.data(), value_text.data() + value_text.size(), value);
    if (n.ec != std::errc() || n.ptr != number_text.data() + number_text.size() || number < 1 || number >= kCount) {
      error = "line " + std::to_string(line_number) + ": '" + number_text + "' is not a parameter number (1.." +
              std::to_string(kCount - 1) + ")";
      return false;
    }
    if (v.ec != std::errc() || v.ptr != value_text.data() + value_text.size() || !std::isfinite(value)) {
      error = "line " + std::to_string(line_number) + ": '" + value_text + "' is not a number";
      return false;
    }
    loaded[static_cast<std::size_t>(number)] = value;
  }
  numbered_ = loaded;
  return true;
}

}  // namespace tnv::gcode
