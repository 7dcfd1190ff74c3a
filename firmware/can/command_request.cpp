// CommandRequest: COMMAND (command_request.hpp).
#include "firmware/can/command_request.hpp"

#include <cmath>

#include "firmware/can/command_result.hpp"
#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"
#include "firmware/can/param_table.hpp"

namespace tnv::fw::can {

using namespace fields;

namespace {

constexpr std::uint8_t kAllAxes = 255;

}  // namespace

void CommandRequest::handle(const hal::CanFrame& frame) noexcept {
  const auto code_raw = static_cast<std::uint8_t>(read_raw(frame, kCommandCode));
  if (code_raw >= kCommandCodeCount) {
    ack_.send(kCommandMsg.id, code_raw, ErrorCode::unknown_command, index_of(kCommandMsg, kCommandCode));
    return;
  }
  const auto code = static_cast<CommandCode>(code_raw);
  const bool broadcast_stop = code == CommandCode::stop && access_.broadcast();
  const bool open_to_all = code == CommandCode::take_ownership || code == CommandCode::release_ownership ||
                           code == CommandCode::program_status || broadcast_stop;
  if (!open_to_all && !access_.owns()) {
    ack_.send(kCommandMsg.id, code_raw, ErrorCode::not_owner, 0);
    return;
  }
  std::uint8_t detail = 0;
  ErrorCode e = ErrorCode::ok;
  switch (code) {
    case CommandCode::enable:
      commissioning_.leave();  // asked for, even if refused
      e = to_error(task_.hold_position());
      break;
    case CommandCode::disable: e = to_error(task_.disable()); break;
    case CommandCode::stop:
      if (task_.program_running()) programs_.stopping();
      e = to_error(task_.stop());
      break;
    case CommandCode::clear_faults: e = to_error(task_.clear_fault()); break;
    case CommandCode::zero: e = zero(frame, detail); break;
    case CommandCode::home: e = home(frame, detail); break;
    case CommandCode::select_controller: e = select_controller(frame, detail); break;
    case CommandCode::shaper_enable: e = shaper_enable(frame, detail); break;
    case CommandCode::save_params:
    case CommandCode::load_params:
      e = storage_.begin(frame, static_cast<CommandCode>(code_raw));
      if (e == ErrorCode::ok) return;  // answered when the storage job is done
      break;
    case CommandCode::restore_defaults: e = params_.restore_defaults(); break;
    case CommandCode::take_ownership:
    case CommandCode::release_ownership:
      e = access_.ownership(code);
      if (e == ErrorCode::ok && code == CommandCode::release_ownership)
        programs_.drop_pending();  // a half-received element of the host that let go
      if (e == ErrorCode::ok && code == CommandCode::take_ownership)
        task_.set_host_lost(false);  // a host is back: lifts the inhibit, starts nothing
      break;
    case CommandCode::enter_commissioning: e = commissioning_.enter(); break;
    case CommandCode::leave_commissioning: commissioning_.leave(); break;
    case CommandCode::feed_hold:
    case CommandCode::feed_resume:
    case CommandCode::feed_override:
    case CommandCode::end_program:
    case CommandCode::abort_program:
    case CommandCode::program_status:
    case CommandCode::cycle_start: e = programs_.command(code, frame, detail); break;
  }
  if (design_.deferred()) return;  // handled again, and answered, when the shaper designs are made
  ack_.send(kCommandMsg.id, code_raw, e, detail);
}

ErrorCode CommandRequest::zero(const hal::CanFrame& frame, std::uint8_t& detail) noexcept {
  const std::uint32_t axis = read_raw(frame, kCommandAxis);
  const double value_mm = read(frame, kCommandValue);
  if (axis >= hal::kAxisCount) {
    detail = index_of(kCommandMsg, kCommandAxis);
    return ErrorCode::bad_axis;
  }
  detail = index_of(kCommandMsg, kCommandValue);
  if (!std::isfinite(value_mm)) return ErrorCode::not_finite;
  const CommandStatus st = task_.zero(hal::axis_from_index(axis), value_mm);
  if (st == CommandStatus::invalid) return ErrorCode::out_of_range;  // outside the soft limits
  if (st == CommandStatus::ok) detail = 0;
  return to_error(st);
}

// COMMAND home: one axis' index, or 255 (every axis, in hal::kHomingOrder).
ErrorCode CommandRequest::home(const hal::CanFrame& frame, std::uint8_t& detail) noexcept {
  const std::uint32_t axis = read_raw(frame, kCommandAxis);
  if (axis >= hal::kAxisCount && axis != kAllAxes) {
    detail = index_of(kCommandMsg, kCommandAxis);
    return ErrorCode::bad_axis;
  }
  commissioning_.leave();  // asked for motion, even if refused (as enable)
  const CommandStatus st =
      task_.home(axis == kAllAxes ? hal::kEveryAxis : hal::axis_bit(hal::axis_from_index(axis)));
  if (st == CommandStatus::ok) motion_.accepted();
  return to_error(st);
}

ErrorCode CommandRequest::select_controller(const hal::CanFrame& frame, std::uint8_t& detail) noexcept {
  const std::uint32_t axis = read_raw(frame, kCommandAxis);
  const std::uint32_t arg = read_raw(frame, kCommandArg);
  if (axis >= hal::kAxisCount && axis != kAllAxes) {
    detail = index_of(kCommandMsg, kCommandAxis);
    return ErrorCode::bad_axis;
  }
  if (arg > 2) {
    detail = index_of(kCommandMsg, kCommandArg);
    return ErrorCode::out_of_range;
  }
  NodeSettings next = params_.settings();
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    if (axis == kAllAxes || axis == i) next.firmware.axis[i].controller = static_cast<ControllerKind>(arg);
  const ParamDef* p = find_param(axis_param_id(0, 0x00));
  return params_.apply(next, p == nullptr || p->apply == Apply::idle);
}

ErrorCode CommandRequest::shaper_enable(const hal::CanFrame& frame, std::uint8_t& detail) noexcept {
  const std::uint32_t axis = read_raw(frame, kCommandAxis);
  const std::uint32_t arg = read_raw(frame, kCommandArg);
  if (axis >= hal::kAxisCount && axis != kAllAxes) {
    detail = index_of(kCommandMsg, kCommandAxis);
    return ErrorCode::bad_axis;
  }
  if (arg > 1) {
    detail = index_of(kCommandMsg, kCommandArg);
    return ErrorCode::out_of_range;
  }
  NodeSettings next = params_.settings();
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    if (axis == kAllAxes || axis == i) next.shaper[i].enabled = arg == 1;
  return params_.apply(next, false);
}

}  // namespace tnv::fw::can
