#pragma once
// One frame per line in candump's log format (`candump -l`, read back by
// canplayer and python-can): "(1700000000.123456) can0 241#0102030405060708".
// Standard identifiers print as 3 hex digits, extended as 8.
#include <optional>
#include <string>

#include "hal/can_port.hpp"

namespace tnv::can_host {

struct CandumpRecord {
  double t_s = 0.0;
  std::string iface;
  hal::CanFrame frame;
};

std::string candump_line(double t_s, const std::string& iface, const hal::CanFrame& frame);

// nullopt with `error` (what is wrong) for a line that is not one frame in
// that format; CAN FD ("##"), remote ("R") and error frames are refused.
std::optional<CandumpRecord> parse_candump_line(const std::string& line, std::string& error);

}  // namespace tnv::can_host
