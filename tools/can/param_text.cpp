#include "tools/can/param_text.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <vector>

namespace tnv::can_host {

namespace {

struct NamedValue {
  long long value;
  std::string name;
};

// "0=pid 1=dvsc 2=rdvsc" -> {0,pid} {1,dvsc} {2,rdvsc}
std::vector<NamedValue> named_values(const char* values) {
  std::vector<NamedValue> out;
  std::istringstream in(values);
  std::string token;
  while (in >> token) {
    const auto eq = token.find('=');
    if (eq == std::string::npos) continue;
    out.push_back({std::atoll(token.substr(0, eq).c_str()), token.substr(eq + 1)});
  }
  return out;
}

std::string number_text(double v, bool integral) {
  char buf[64];
  if (integral) {
    std::snprintf(buf, sizeof buf, "%.0f", v);
    return buf;
  }
  // The shortest text that reads back as the same float32 (parameters
  // travel and are stored as float32): 0.4155, not 0.415499985; plain
  // decimals while they stay short, 200 rather than 2e+02.
  const auto same = [&] { return static_cast<float>(std::strtod(buf, nullptr)) == static_cast<float>(v); };
  for (int decimals = 0; decimals <= 10; ++decimals) {
    const int n = std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    if (n > 12) break;
    if (same()) return buf;
  }
  for (int digits = 1; digits <= 9; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (same()) break;
  }
  return buf;
}

std::optional<double> parse_number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const bool hex = text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X');
  const double v = hex ? static_cast<double>(std::strtoull(text.c_str(), &end, 16)) : std::strtod(text.c_str(), &end);
  if (end == nullptr || *end != '\0' || errno == ERANGE) return std::nullopt;
  return v;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0u : 1u)});
      diag = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string format_param_value(const can::ParamDef& p, double value) {
  if (p.values[0] != '\0')
    for (const NamedValue& nv : named_values(p.values))
      if (static_cast<double>(nv.value) == value) return nv.name;
  return number_text(value, p.type != can::ParamType::f32);
}

std::string range_text(const can::ParamDef& p) {
  if (p.values[0] != '\0') {
    std::string out = "{";
    for (const NamedValue& nv : named_values(p.values)) {
      if (out.size() > 1) out += ", ";
      out += nv.name;
    }
    return out + "}";
  }
  if (p.allowed != nullptr) {
    std::string out = "{";
    for (double v = p.min; v <= p.max; v += 1.0)
      if (p.allowed(v)) {
        if (out.size() > 1) out += ", ";
        out += number_text(v, true);
      }
    return out + "}";
  }
  const bool integral = p.type != can::ParamType::f32;
  return number_text(p.min, integral) + " .. " + number_text(p.max, integral);
}

std::optional<double> parse_param_value(const can::ParamDef& p, const std::string& text, std::string& error) {
  std::optional<double> value;
  if (p.values[0] != '\0') {
    for (const NamedValue& nv : named_values(p.values))
      if (nv.name == text) value = static_cast<double>(nv.value);
    if (!value && p.type == can::ParamType::boolean) {
      if (text == "true" || text == "yes") value = 1.0;
      if (text == "false" || text == "no") value = 0.0;
    }
  }
  if (!value) value = parse_number(text);
  if (!value) {
    error = p.name;
    error.append(": '").append(text).append("' is not a ");
    error += p.values[0] != '\0' ? "value of " + range_text(p) : std::string("number");
    return std::nullopt;
  }
  switch (can::check_value(p, *value)) {
    case can::ErrorCode::ok: return value;
    case can::ErrorCode::read_only:
      error = p.name;
      error += ": read-only";
      return std::nullopt;
    case can::ErrorCode::not_finite:
      error = p.name;
      error += ": not a finite number";
      return std::nullopt;
    default:
      error = p.name;
      error.append(": ").append(text).append(" is outside ").append(range_text(p));
      if (p.type != can::ParamType::f32 && p.values[0] == '\0') error += " (whole numbers)";
      return std::nullopt;
  }
}

const can::ParamDef* find_param_by_text(const std::string& name_or_id) {
  if (const can::ParamDef* p = can::find_param(name_or_id.c_str())) return p;
  const std::optional<double> id = parse_number(name_or_id);
  if (id && *id >= 0 && *id <= 65535 && *id == std::floor(*id)) return can::find_param(static_cast<std::uint16_t>(*id));
  return nullptr;
}

std::vector<const can::ParamDef*> params_matching(const std::string& pattern) {
  if (const can::ParamDef* p = find_param_by_text(pattern)) return {p};
  std::vector<const can::ParamDef*> found;
  if (pattern.empty()) return found;
  const bool glob = pattern.find_first_of("*?[") != std::string::npos;
  const std::string prefix = pattern.back() == '.' ? pattern : pattern + ".";
  for (const can::ParamDef& p : can::param_table()) {
    const bool match = glob ? ::fnmatch(pattern.c_str(), p.name, 0) == 0 : std::string_view(p.name).starts_with(prefix);
    if (match) found.push_back(&p);
  }
  return found;
}

std::string closest_param_name(const std::string& name) {
  std::string best;
  std::size_t best_distance = 4;  // at most 3 edits away
  for (const can::ParamDef& p : can::param_table()) {
    const std::size_t d = edit_distance(name, p.name);
    if (d < best_distance) {
      best_distance = d;
      best = p.name;
    }
  }
  return best;
}

}  // namespace tnv::can_host
