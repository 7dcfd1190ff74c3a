#include "tools/can/capture_csv.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace tnv::can_host {

namespace {

void append_value(std::string& out, const can::ChannelDef& c, double v) {
  char buf[48];
  if (c.type == can::WireType::f32) std::snprintf(buf, sizeof buf, "%.9g", v);
  else if (c.scale == 1.0) std::snprintf(buf, sizeof buf, "%.0f", v);
  else std::snprintf(buf, sizeof buf, "%.6f", v);  // 1e-6 mm steps: exact to the nm
  out += buf;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

}  // namespace

std::string capture_csv(const CaptureTable& table) {
  std::string out = "t_s";
  for (const can::ChannelDef* c : table.channels) out.append(",").append(column_name(*c));
  out += '\n';
  char buf[32];
  for (std::size_t s = 0; s < table.samples(); ++s) {
    std::snprintf(buf, sizeof buf, "%.3f", static_cast<double>(s) * table.period_s());
    out += buf;
    for (std::size_t c = 0; c < table.channels.size(); ++c) {
      out += ',';
      append_value(out, *table.channels[c], table.columns[c][s]);
    }
    out += '\n';
  }
  return out;
}

std::optional<CaptureTable> read_capture_csv(const std::string& text, std::string& error) {
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line)) {
    error = "empty file";
    return std::nullopt;
  }
  const std::vector<std::string> header = split(line);
  if (header.empty() || header[0] != "t_s") {
    error = "line 1: not a tnvctl capture (the first column must be t_s)";
    return std::nullopt;
  }
  CaptureTable t;
  for (std::size_t i = 1; i < header.size(); ++i) {
    const can::ChannelDef* found = nullptr;
    for (const can::ChannelDef& c : can::kCaptureChannels)
      if (header[i] == column_name(c)) found = &c;
    if (found == nullptr) {
      error = "line 1: unknown column '";
      error.append(header[i]).append("'");
      return std::nullopt;
    }
    t.channels.push_back(found);
  }
  t.columns.resize(t.channels.size());
  std::vector<double> times;
  int line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    const std::vector<std::string> cells = split(line);
    if (cells.size() != header.size()) {
      error = "line ";
      error.append(std::to_string(line_number)).append(": ").append(std::to_string(cells.size()));
      error.append(" values, the header has ").append(std::to_string(header.size()));
      return std::nullopt;
    }
    for (std::size_t i = 0; i < cells.size(); ++i) {
      char* end = nullptr;
      const double v = std::strtod(cells[i].c_str(), &end);
      if (cells[i].empty() || end == nullptr || *end != '\0' || !std::isfinite(v)) {
        error = "line ";
        error.append(std::to_string(line_number)).append(", column ").append(header[i]).append(": '");
        error.append(cells[i]).append("' is not a finite number");
        return std::nullopt;
      }
      if (i == 0) times.push_back(v);
      else t.columns[i - 1].push_back(v);
    }
  }
  if (times.size() >= 2) t.decimation = static_cast<std::uint32_t>(std::lround((times[1] - times[0]) * 1000.0));
  if (t.decimation == 0) t.decimation = 1;
  return t;
}

}  // namespace tnv::can_host
