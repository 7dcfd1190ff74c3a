// CanNode: COMMAND, JOG, MOVE, CIRCLE and SHAPER, each answered by one
// COMMAND_ACK (detail = index of the offending field). Every check comes
// before anything is started: a refused request changes nothing. All of
// them need command ownership (the broadcast stop excepted); taking and
// releasing it are COMMAND codes too.
#include <cmath>

#include "firmware/can/can_node.hpp"
#include "firmware/can/command_result.hpp"
#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"
#include "firmware/can/request_tag.hpp"

namespace tnv::fw::can {

using namespace fields;

namespace {

constexpr std::uint8_t kAllAxes = 255;

std::uint16_t axis_param(std::size_t axis, std::uint16_t low) noexcept {
  return static_cast<std::uint16_t>(axis_param_base(hal::axis_from_index(axis)) + low);
}

}  // namespace

void CanNode::motion_accepted() noexcept {
  commissioning_.leave();
  telemetry_.motion_accepted();
}

void CanNode::handle_command(const hal::CanFrame& frame) noexcept {
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
    case CommandCode::zero: e = command_zero(frame, detail); break;
    case CommandCode::home: e = command_home(frame, detail); break;
    case CommandCode::select_controller: e = command_select_controller(frame, detail); break;
    case CommandCode::shaper_enable: e = command_shaper_enable(frame, detail); break;
    case CommandCode::save_params:
    case CommandCode::load_params:
      e = begin_storage(frame, static_cast<CommandCode>(code_raw));
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

ErrorCode CanNode::command_zero(const hal::CanFrame& frame, std::uint8_t& detail) noexcept {
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
ErrorCode CanNode::command_home(const hal::CanFrame& frame, std::uint8_t& detail) noexcept {
  const std::uint32_t axis = read_raw(frame, kCommandAxis);
  if (axis >= hal::kAxisCount && axis != kAllAxes) {
    detail = index_of(kCommandMsg, kCommandAxis);
    return ErrorCode::bad_axis;
  }
  commissioning_.leave();  // asked for motion, even if refused (as enable)
  const CommandStatus st =
      task_.home(axis == kAllAxes ? hal::kEveryAxis : hal::axis_bit(hal::axis_from_index(axis)));
  if (st == CommandStatus::ok) motion_accepted();
  return to_error(st);
}

ErrorCode CanNode::command_select_controller(const hal::CanFrame& frame, std::uint8_t& detail) noexcept {
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
  const ParamDef* p = find_param(axis_param(0, 0x00));
  return params_.apply(next, p == nullptr || p->apply == Apply::idle);
}

ErrorCode CanNode::command_shaper_enable(const hal::CanFrame& frame, std::uint8_t& detail) noexcept {
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

void CanNode::handle_jog(const hal::CanFrame& frame) noexcept {
  if (!access_.owns()) return ack_.send(kJogMsg.id, 0, ErrorCode::not_owner, 0);
  const std::uint32_t axis = read_raw(frame, kJogAxis);
  if (axis >= hal::kAxisCount) return ack_.send(kJogMsg.id, 0, ErrorCode::bad_axis, index_of(kJogMsg, kJogAxis));
  const double speed_mm_s = read(frame, kJogSpeed);
  const std::uint8_t detail = index_of(kJogMsg, kJogSpeed);
  if (!std::isfinite(speed_mm_s)) return ack_.send(kJogMsg.id, 0, ErrorCode::not_finite, detail);
  if (std::fabs(speed_mm_s) > task_.config().axis[axis].jog.speed_max_mm_s)
    return ack_.send(kJogMsg.id, 0, ErrorCode::out_of_range, detail);
  ErrorCode e = ErrorCode::ok;
  if (task_.state() == MotionState::faulted) {
    e = ErrorCode::faulted;
  } else if ((task_.state() != MotionState::holding && !task_.jogging()) || task_.stopping()) {
    e = ErrorCode::busy;
  } else {
    e = to_error(task_.jog(hal::axis_from_index(axis), speed_mm_s));
  }
  if (e == ErrorCode::ok) motion_accepted();
  ack_.send(kJogMsg.id, 0, e, 0);
}

void CanNode::handle_move(const hal::CanFrame& frame) noexcept {
  if (!access_.owns()) return ack_.send(kMoveMsg.id, 0, ErrorCode::not_owner, 0);
  const std::uint32_t axis = read_raw(frame, kMoveAxis);
  const double speed_mm_s = read(frame, kMoveSpeed);
  const double distance_mm = read(frame, kMoveDistance);
  if (axis >= hal::kAxisCount) return ack_.send(kMoveMsg.id, 0, ErrorCode::bad_axis, index_of(kMoveMsg, kMoveAxis));
  if (!(speed_mm_s > 0.0)) return ack_.send(kMoveMsg.id, 0, ErrorCode::out_of_range, index_of(kMoveMsg, kMoveSpeed));
  const std::uint8_t distance = index_of(kMoveMsg, kMoveDistance);
  if (!std::isfinite(distance_mm)) return ack_.send(kMoveMsg.id, 0, ErrorCode::not_finite, distance);
  MoveSpec spec;
  spec.axis = hal::axis_from_index(axis);
  spec.distance_mm = distance_mm;
  spec.speed_mm_s = speed_mm_s;
  spec.ramp_s = params_.settings().motion.move_ramp_s;
  spec.dwell_s = params_.settings().motion.move_dwell_s;
  // A zero distance, or one too short for the two ramps at this speed.
  if (validate(spec)[0] != '\0') return ack_.send(kMoveMsg.id, 0, ErrorCode::invalid, distance);
  const CommandStatus st = task_.start_move(spec);
  if (st == CommandStatus::invalid) return ack_.send(kMoveMsg.id, 0, ErrorCode::out_of_range, distance);  // soft limits
  if (st == CommandStatus::ok) motion_accepted();
  ack_.send(kMoveMsg.id, 0, to_error(st), 0);
}

// The circle starts where the table stands, which is on the circle at
// (+r, 0) from its centre. Standing at (r, 0) of the machine frame (within
// the following-error floor, as after homing or zero) the circle is run
// about the origin itself, exactly as tnv-hil runs it; anywhere else about
// (standing - (r, 0)).
void CanNode::handle_circle(const hal::CanFrame& frame) noexcept {
  if (!access_.owns()) return ack_.send(kCircleMsg.id, 0, ErrorCode::not_owner, 0);
  const double radius_mm = read(frame, kCircleRadius);
  const double feed_mm_s = read(frame, kCircleFeed);
  const std::uint8_t radius = index_of(kCircleMsg, kCircleRadius);
  const std::uint8_t feed = index_of(kCircleMsg, kCircleFeed);
  if (!std::isfinite(radius_mm)) return ack_.send(kCircleMsg.id, 0, ErrorCode::not_finite, radius);
  if (!std::isfinite(feed_mm_s)) return ack_.send(kCircleMsg.id, 0, ErrorCode::not_finite, feed);
  if (!(radius_mm > 0.0)) return ack_.send(kCircleMsg.id, 0, ErrorCode::out_of_range, radius);
  if (!(feed_mm_s > 0.0)) return ack_.send(kCircleMsg.id, 0, ErrorCode::out_of_range, feed);
  const MotionDefaults& defaults = params_.settings().motion;
  const CircleSpec spec{radius_mm, feed_mm_s, defaults.circle_ramp_s, defaults.circle_dwell_s};
  if (validate(spec)[0] != '\0') return ack_.send(kCircleMsg.id, 0, ErrorCode::invalid, radius);
  // The circle lies in the XY plane.
  const double x_mm = task_.standing_mm(hal::kPlaneFirst);
  const double y_mm = task_.standing_mm(hal::kPlaneSecond);
  const SupervisorConfig& sup = task_.config().supervisor;
  const bool on_origin_circle =
      std::fabs(x_mm - radius_mm) < sup.axis[hal::index(hal::kPlaneFirst)].following.floor_mm &&
      std::fabs(y_mm) < sup.axis[hal::index(hal::kPlaneSecond)].following.floor_mm;
  const CommandStatus st =
      on_origin_circle ? task_.start_circle(spec) : task_.start_circle(spec, x_mm - radius_mm, y_mm);
  if (st == CommandStatus::ok) motion_accepted();
  ack_.send(kCircleMsg.id, 0, to_error(st), 0);
}

// Same as staging x|y.shaper.type/freq_hz/zeta and committing.
void CanNode::handle_shaper(const hal::CanFrame& frame) noexcept {
  if (!access_.owns()) return ack_.send(kShaperMsg.id, 0, ErrorCode::not_owner, 0);
  const std::uint32_t axis = read_raw(frame, kShaperAxis);
  const std::uint32_t type = read_raw(frame, kShaperType);
  const double zeta = read(frame, kShaperZeta);
  const double freq_hz = read(frame, kShaperFreq);
  if (axis >= hal::kAxisCount) return ack_.send(kShaperMsg.id, 0, ErrorCode::bad_axis, index_of(kShaperMsg, kShaperAxis));
  const std::array<std::pair<const FieldDef*, std::uint16_t>, 3> checks{
      {{&kShaperType, axis_param(axis, 0x40)}, {&kShaperZeta, axis_param(axis, 0x42)}, {&kShaperFreq, axis_param(axis, 0x41)}}};
  const std::array<double, 3> values{static_cast<double>(type), zeta, freq_hz};
  NodeSettings next = params_.settings();
  for (std::size_t k = 0; k < checks.size(); ++k) {
    const ParamDef* p = find_param(checks[k].second);
    const std::uint8_t detail = index_of(kShaperMsg, *checks[k].first);
    if (p == nullptr) return ack_.send(kShaperMsg.id, 0, ErrorCode::unknown_id, detail);
    if (const ErrorCode e = check_value(*p, values[k]); e != ErrorCode::ok) return ack_.send(kShaperMsg.id, 0, e, detail);
    p->set(next, values[k]);
  }
  const ErrorCode e = params_.apply(next, false);
  if (design_.deferred()) return;  // handled again, and answered, when the design is made
  ack_.send(kShaperMsg.id, 0, e, 0);
}

}  // namespace tnv::fw::can
