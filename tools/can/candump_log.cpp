#include "tools/can/candump_log.hpp"

#include <cstdio>
#include <cstdlib>

namespace tnv::can_host {

namespace {

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

std::string candump_line(double t_s, const std::string& iface, const hal::CanFrame& frame) {
  char buf[96];
  int n = std::snprintf(buf, sizeof buf, "(%.6f) %s ", t_s, iface.c_str());
  if (n < 0 || static_cast<std::size_t>(n) >= sizeof buf) n = 0;
  std::string line(buf, static_cast<std::size_t>(n));
  std::snprintf(buf, sizeof buf, frame.extended ? "%08X#" : "%03X#", static_cast<unsigned>(frame.id));
  line += buf;
  for (std::size_t i = 0; i < frame.dlc && i < frame.data.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%02X", frame.data[i]);
    line += buf;
  }
  return line;
}

std::optional<CandumpRecord> parse_candump_line(const std::string& line, std::string& error) {
  CandumpRecord r;
  if (line.size() < 3 || line[0] != '(') {
    error = "expected \"(SECONDS) IFACE ID#DATA\"";
    return std::nullopt;
  }
  char* end = nullptr;
  r.t_s = std::strtod(line.c_str() + 1, &end);
  if (end == line.c_str() + 1 || *end != ')' || !(r.t_s >= 0.0)) {
    error = "bad timestamp";
    return std::nullopt;
  }
  std::size_t at = static_cast<std::size_t>(end - line.c_str()) + 1;
  while (at < line.size() && line[at] == ' ') ++at;
  const std::size_t iface_end = line.find(' ', at);
  if (iface_end == std::string::npos || iface_end == at) {
    error = "no interface name";
    return std::nullopt;
  }
  r.iface = line.substr(at, iface_end - at);
  at = iface_end;
  while (at < line.size() && line[at] == ' ') ++at;
  const std::size_t hash = line.find('#', at);
  if (hash == std::string::npos) {
    error = "no '#' between identifier and data";
    return std::nullopt;
  }
  const std::string id_text = line.substr(at, hash - at);
  if (id_text.empty() || (id_text.size() != 3 && id_text.size() != 8)) {
    error = "identifier must be 3 (standard) or 8 (extended) hex digits";
    return std::nullopt;
  }
  std::uint32_t id = 0;
  for (const char c : id_text) {
    const int d = hex_digit(c);
    if (d < 0) {
      error = "identifier is not hex";
      return std::nullopt;
    }
    id = id << 4 | static_cast<std::uint32_t>(d);
  }
  r.frame.extended = id_text.size() == 8;
  if ((r.frame.extended && id > 0x1FFFFFFFu) || (!r.frame.extended && id > 0x7FFu)) {
    error = "error frames and out-of-range identifiers are not replayed";
    return std::nullopt;
  }
  r.frame.id = id;
  std::string data = line.substr(hash + 1);
  while (!data.empty() && (data.back() == '\r' || data.back() == ' ')) data.pop_back();
  if (!data.empty() && (data[0] == '#' || data[0] == 'R')) {
    error = "CAN FD and remote frames are not part of this protocol";
    return std::nullopt;
  }
  if (data.size() % 2 != 0 || data.size() > 16) {
    error = "data must be 0 to 8 bytes as hex pairs";
    return std::nullopt;
  }
  r.frame.dlc = static_cast<std::uint8_t>(data.size() / 2);
  for (std::size_t i = 0; i < r.frame.dlc; ++i) {
    const int hi = hex_digit(data[2 * i]);
    const int lo = hex_digit(data[2 * i + 1]);
    if (hi < 0 || lo < 0) {
      error = "data is not hex";
      return std::nullopt;
    }
    r.frame.data[i] = static_cast<std::uint8_t>(hi << 4 | lo);
  }
  return r;
}

}  // namespace tnv::can_host
