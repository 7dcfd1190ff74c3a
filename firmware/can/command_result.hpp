#pragma once
// TickTask's CommandStatus as the protocol's ErrorCode.
#include "firmware/can/protocol_enums.hpp"
#include "firmware/tick/tick_task.hpp"

namespace tnv::fw::can {

constexpr ErrorCode to_error(CommandStatus s) noexcept {
  switch (s) {
    case CommandStatus::ok: return ErrorCode::ok;
    case CommandStatus::busy: return ErrorCode::busy;
    case CommandStatus::faulted: return ErrorCode::faulted;
    case CommandStatus::invalid: return ErrorCode::invalid;
    case CommandStatus::cause_present: return ErrorCode::cause_present;
    case CommandStatus::not_homed: return ErrorCode::not_homed;
    case CommandStatus::spindle_running: return ErrorCode::spindle_running;
    case CommandStatus::not_paused: return ErrorCode::not_ready;
  }
  return ErrorCode::invalid;
}

}  // namespace tnv::fw::can
