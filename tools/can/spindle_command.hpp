#pragma once
// A SPINDLE request from the host (docs/safety.md "Spindle"): the speed
// checked before anything is sent, then the request and the node's answer.
// What `tnvctl spindle` and the Python module's spindle_start / _stop send.
#include <string_view>

#include "firmware/can/protocol_enums.hpp"
#include "firmware/spindle/spindle_control.hpp"
#include "tools/can/node_client.hpp"

namespace tnv::can_host {

// start and speed: a finite rpm in (0, the drive's full scale]; the node
// refuses more than spindle.max_rpm itself. stop takes no speed. Throws
// std::invalid_argument naming the limit.
void check_spindle_rpm(fw::can::SpindleOp op, double rpm);

// "forward" (M3) or "reverse" (M4); std::invalid_argument otherwise.
fw::SpindleDirection spindle_direction_named(std::string_view name);

// check_spindle_rpm, then NodeClient::spindle: returns once the node
// acknowledged (the spindle then ramps on its own); a refusal throws RequestError.
CommandAck spindle_command(NodeClient& client, fw::can::SpindleOp op,
                           fw::SpindleDirection direction = fw::SpindleDirection::forward, double rpm = 0.0);

}  // namespace tnv::can_host
