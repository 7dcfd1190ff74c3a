#pragma once
// A refused command as the operator reads it: "faulted" names the latched
// fault and its axis ("faulted (encoder_error, axis x)"), not only the status.
#include <string>

#include "firmware/tick/tick_task.hpp"

namespace tnv::hil {

std::string command_status_text(fw::CommandStatus status, const fw::TickTask& task);

}  // namespace tnv::hil
