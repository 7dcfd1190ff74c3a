// MotionRequests: JOG, MOVE and CIRCLE (motion_requests.hpp).
#include "firmware/can/motion_requests.hpp"

#include <cmath>

#include "firmware/can/command_result.hpp"
#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"

namespace tnv::fw::can {

using namespace fields;

void MotionRequests::jog(const hal::CanFrame& frame) noexcept {
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
  if (e == ErrorCode::ok) motion_.accepted();
  ack_.send(kJogMsg.id, 0, e, 0);
}

void MotionRequests::move(const hal::CanFrame& frame) noexcept {
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
  if (st == CommandStatus::ok) motion_.accepted();
  ack_.send(kMoveMsg.id, 0, to_error(st), 0);
}

// The circle starts where the table stands, which is on the circle at
// (+r, 0) from its centre. Standing at (r, 0) of the machine frame (within
// the following-error floor, as after homing or zero) the circle is run
// about the origin itself, exactly as tnv-hil runs it; anywhere else about
// (standing - (r, 0)).
void MotionRequests::circle(const hal::CanFrame& frame) noexcept {
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
  if (st == CommandStatus::ok) motion_.accepted();
  ack_.send(kCircleMsg.id, 0, to_error(st), 0);
}

}  // namespace tnv::fw::can
