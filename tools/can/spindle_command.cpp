#include "tools/can/spindle_command.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "firmware/spindle/spindle_params.hpp"

namespace tnv::can_host {

void check_spindle_rpm(fw::can::SpindleOp op, double rpm) {
  if (op == fw::can::SpindleOp::stop) return;
  if (std::isfinite(rpm) && rpm > 0.0 && rpm <= fw::kSpindleDriveFullScaleRpm) return;
  char buf[128];
  std::snprintf(buf, sizeof buf, "the speed must be > 0 and <= %g rpm (got %g)", fw::kSpindleDriveFullScaleRpm, rpm);
  throw std::invalid_argument(buf);
}

fw::SpindleDirection spindle_direction_named(std::string_view name) {
  for (const fw::SpindleDirection d : fw::kSpindleDirections)
    if (name == fw::to_string(d)) return d;
  throw std::invalid_argument("the direction must be forward or reverse, not '" + std::string(name) + "'");
}

CommandAck spindle_command(NodeClient& client, fw::can::SpindleOp op, fw::SpindleDirection direction, double rpm) {
  check_spindle_rpm(op, rpm);
  return client.spindle(op, direction, op == fw::can::SpindleOp::stop ? 0.0 : rpm);
}

}  // namespace tnv::can_host
