#pragma once
// One frame of the protocol as a person reads it (`tnvctl decode`): the
// message and node, then each field by name with its unit, enumerations by
// name, heartbeat bits by name, and a parameter request's or reply's value
// typed by its parameter (x.sliding.gamma=0.25, not 1048576000).
#include <string>

#include "hal/can_port.hpp"

namespace tnv::can_host {

std::string frame_text(const hal::CanFrame& frame);

}  // namespace tnv::can_host
