#include "tools/can/path_telemetry.hpp"

#include "firmware/can/node_fields.hpp"

namespace tnv::can_host {

namespace f = fw::can::fields;

void PathTelemetry::take(const hal::CanFrame& frame, can::MessageId id) {
  const auto raw_i32 = [&](const can::FieldDef& field) { return static_cast<std::int32_t>(can::read_raw(frame, field)); };
  switch (id) {
    // Paths lie in the XY plane.
    case can::MessageId::tlm_position:
      positions_.push_back({raw_i32(*f::kPositionFields[hal::index(hal::kPlaneFirst)]),
                            raw_i32(*f::kPositionFields[hal::index(hal::kPlaneSecond)])});
      break;
    case can::MessageId::tlm_following:
      if (positions_.empty() && samples_.empty()) return;  // its position came before counting began
      followings_.push_back({raw_i32(*f::kFollowingFields[hal::index(hal::kPlaneFirst)]),
                             raw_i32(*f::kFollowingFields[hal::index(hal::kPlaneSecond)])});
      break;
    case can::MessageId::heartbeat:
      if (!samples_.empty() && (read_heartbeat(frame).errors & can::kHbTxDropped) != 0) dropped_ = true;
      return;
    default: return;
  }
  while (!positions_.empty() && !followings_.empty()) {
    const std::array<std::int32_t, 2> p = positions_.front();
    const std::array<std::int32_t, 2> q = followings_.front();
    positions_.pop_front();
    followings_.pop_front();
    hil::PathSample s;
    for (std::size_t i = 0; i < 2; ++i) {
      // Sum the integers, then scale: one rounding instead of three.
      s.position_mm[i] = static_cast<double>(p[i]) * f::kPositionFields[0]->scale;
      s.reference_mm[i] = static_cast<double>(static_cast<std::int64_t>(p[i]) + q[i]) * f::kPositionFields[0]->scale;
    }
    samples_.push_back(s);
  }
}

std::optional<fw::motion::PlanePoint> PathTelemetry::last_reference() const {
  if (samples_.empty()) return std::nullopt;
  return samples_.back().reference_mm;
}

}  // namespace tnv::can_host
