#include "tools/can/path_telemetry.hpp"

#include "firmware/can/node_fields.hpp"

namespace tnv::can_host {

namespace f = fw::can::fields;

void PathTelemetry::take(const hal::CanFrame& frame, can::MessageId id) {
  const auto raw_i32 = [&](const can::FieldDef& field) { return static_cast<std::int32_t>(can::read_raw(frame, field)); };
  if (id == can::MessageId::heartbeat) {
    if (!samples_.empty() && (read_heartbeat(frame).errors & can::kHbTxDropped) != 0) dropped_ = true;
    return;
  }
  // Paths lie in the XY plane: the other axes' frames are not part of a sample.
  const auto a = f::axis_of(f::kPositionMsgs, static_cast<std::uint8_t>(id));
  if (!a) return;
  const std::array<std::int32_t, 2> here{raw_i32(f::kPosition), raw_i32(f::kFollowing)};
  if (*a == hal::kPlaneFirst) {
    first_ = here;
    return;
  }
  if (*a != hal::kPlaneSecond || !first_) return;
  hil::PathSample s;
  const std::array<std::array<std::int32_t, 2>, 2> plane{*first_, here};
  first_.reset();
  for (std::size_t i = 0; i < 2; ++i) {
    // Sum the integers, then scale: one rounding instead of three.
    s.position_mm[i] = static_cast<double>(plane[i][0]) * f::kPosition.scale;
    s.reference_mm[i] = static_cast<double>(static_cast<std::int64_t>(plane[i][0]) + plane[i][1]) * f::kPosition.scale;
  }
  samples_.push_back(s);
}

std::optional<fw::motion::PlanePoint> PathTelemetry::last_reference() const {
  if (samples_.empty()) return std::nullopt;
  return samples_.back().reference_mm;
}

}  // namespace tnv::can_host
