#include "drivers/linux/gpio_lines.hpp"

namespace tnv::drivers {

std::string LineSpec::describe() const {
  if (!name.empty()) return name;
  std::string out = chip;
  out.append(":").append(std::to_string(offset));
  return out;
}

const char* line_key(InputLine line) noexcept {
  switch (line) {
    case InputLine::estop: return "estop";
    case InputLine::alarm_x: return "alarm_x";
    case InputLine::alarm_y: return "alarm_y";
    case InputLine::limit_x_pos: return "limit_x_pos";
    case InputLine::limit_x_neg: return "limit_x_neg";
    case InputLine::limit_y_pos: return "limit_y_pos";
    case InputLine::limit_y_neg: return "limit_y_neg";
  }
  return "?";
}

const char* line_key(OutputLine line) noexcept { return line == OutputLine::enable_x ? "enable_x" : "enable_y"; }

bool LineConfig::any() const noexcept {
  if (tick.configured()) return true;
  for (const LineSpec& s : inputs) {
    if (s.configured()) return true;
  }
  for (const LineSpec& s : outputs) {
    if (s.configured()) return true;
  }
  return false;
}

}  // namespace tnv::drivers
