#include "tools/hil/gauge_file.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string_view>

namespace tnv::hil {

namespace {

constexpr std::string_view kHeader = "position_mm,direction,table_mm";

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

bool parse_number(std::string_view field, double& out) {
  field = trim(field);
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);
  const char* end = field.data() + field.size();
  const auto [ptr, ec] = std::from_chars(field.data(), end, out);
  return ec == std::errc{} && ptr == end && std::isfinite(out);
}

}  // namespace

std::string write_gauge_file(const std::string& comment, const std::vector<GaugePoint>& points) {
  std::string out;
  std::istringstream lines(comment);
  // Appended piece by piece: GCC 12 at -O1 with ThreadSanitizer reports a
  // false -Warray-bounds on `std::string(...) + "\n"` here.
  for (std::string line; std::getline(lines, line);) {
    out += "# ";
    out += line;
    out += '\n';
  }
  out += kHeader;
  out += '\n';
  char row[96];
  for (const GaugePoint& p : points) {
    std::snprintf(row, sizeof row, "%.6f,%d,%.6f\n", p.position_mm, p.direction, p.table_mm);
    out += row;
  }
  return out;
}

std::optional<std::vector<GaugePoint>> read_gauge_file(const std::string& text, std::string& error) {
  std::vector<GaugePoint> points;
  bool header = false;
  std::size_t line_no = 0;
  std::istringstream lines(text);
  for (std::string raw; std::getline(lines, raw);) {
    ++line_no;
    const std::string_view line = trim(raw);
    if (line.empty() || line.front() == '#') continue;
    const std::string where = "line " + std::to_string(line_no) + ": ";
    if (!header) {
      if (line != kHeader) {
        error = where + "expected the header '" + std::string(kHeader) + "'";
        return std::nullopt;
      }
      header = true;
      continue;
    }
    const std::size_t c1 = line.find(',');
    const std::size_t c2 = c1 == std::string_view::npos ? c1 : line.find(',', c1 + 1);
    if (c2 == std::string_view::npos || line.find(',', c2 + 1) != std::string_view::npos) {
      error = where + "expected 3 comma-separated values (position_mm,direction,table_mm)";
      return std::nullopt;
    }
    GaugePoint p;
    double direction = 0.0;
    if (!parse_number(line.substr(0, c1), p.position_mm)) {
      error = where + "position_mm is not a finite number";
      return std::nullopt;
    }
    if (!parse_number(line.substr(c1 + 1, c2 - c1 - 1), direction) || (direction != 1.0 && direction != -1.0)) {
      error = where + "direction must be 1 or -1 (the direction the axis came from)";
      return std::nullopt;
    }
    if (!parse_number(line.substr(c2 + 1), p.table_mm)) {
      error = where + "table_mm is not a finite number";
      return std::nullopt;
    }
    p.direction = static_cast<int>(direction);
    points.push_back(p);
  }
  if (!header) {
    error = "no header line '" + std::string(kHeader) + "'";
    return std::nullopt;
  }
  if (points.empty()) {
    error = "no measured points after the header";
    return std::nullopt;
  }
  return points;
}

}  // namespace tnv::hil
