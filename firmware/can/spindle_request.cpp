// SpindleRequest: SPINDLE (spindle_request.hpp).
#include "firmware/can/spindle_request.hpp"

#include <cmath>

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"

namespace tnv::fw::can {

using namespace fields;

namespace {

ErrorCode spindle_error(SpindleResult r) noexcept {
  switch (r) {
    case SpindleResult::ok: return ErrorCode::ok;
    case SpindleResult::inhibited: return ErrorCode::faulted;  // a fault, the e-stop or a lost host: clear it first
    case SpindleResult::bad_speed: return ErrorCode::out_of_range;
    case SpindleResult::not_running: return ErrorCode::not_ready;  // a speed needs a start first
    case SpindleResult::busy: return ErrorCode::spindle_running;
    case SpindleResult::invalid: break;
  }
  return ErrorCode::invalid;
}

}  // namespace

void SpindleRequest::handle(const hal::CanFrame& frame) noexcept {
  const auto op_raw = static_cast<std::uint8_t>(read_raw(frame, kSpindleOp));
  const auto answer = [&](ErrorCode e, std::uint8_t detail) noexcept { ack_.send(kSpindleMsg.id, op_raw, e, detail); };
  if (op_raw >= kSpindleOpCount) return answer(ErrorCode::unknown_command, index_of(kSpindleMsg, kSpindleOp));
  if (!access_.owns()) return answer(ErrorCode::not_owner, 0);
  const auto op = static_cast<SpindleOp>(op_raw);
  if (op == SpindleOp::stop) {
    task_.spindle_stop();
    return answer(ErrorCode::ok, 0);
  }
  // While a program runs (or holds, or waits at a pause) its own spindle
  // elements set the spindle: a start or a new speed from the side would
  // cut at a speed the program never asked for. A stop is always taken.
  if (active(programs_.tracker().state())) return answer(ErrorCode::busy, 0);
  const std::uint32_t direction = read_raw(frame, kSpindleDirection);
  if (op == SpindleOp::start && direction >= kSpindleDirectionCount)
    return answer(ErrorCode::out_of_range, index_of(kSpindleMsg, kSpindleDirection));
  const double rpm = read(frame, kSpindleRpm);
  const std::uint8_t rpm_field = index_of(kSpindleMsg, kSpindleRpm);
  if (!std::isfinite(rpm)) return answer(ErrorCode::not_finite, rpm_field);
  const SpindleResult r = op == SpindleOp::start
                              ? task_.spindle_start(static_cast<SpindleDirection>(direction), rpm)
                              : task_.spindle_set_speed(rpm);
  if (r == SpindleResult::ok) motion_.accepted();
  answer(spindle_error(r), r == SpindleResult::bad_speed ? rpm_field : 0);
}

}  // namespace tnv::fw::can
