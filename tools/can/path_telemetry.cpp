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
  // A sample is the plane's pair and the Z that follows it; other axes' frames are not part of it.
  const auto a = f::axis_of(f::kPositionMsgs, static_cast<std::uint8_t>(id));
  if (!a) return;
  const std::array<std::int32_t, 2> here{raw_i32(f::kPosition), raw_i32(f::kFollowing)};
  if (*a == hal::kPlaneFirst) {
    first_ = here;
    return;
  }
  if (*a == hal::Axis::z) {
    // Z's frame follows the plane's pair of its tick: it completes that sample (a program may move Z).
    z_ = here;
    if (z_pending_ && !samples_.empty()) set_z(samples_.back());
    z_pending_ = false;
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
  set_z(s);  // the last Z until this tick's comes
  z_pending_ = true;
  samples_.push_back(s);
}

void PathTelemetry::set_z(hil::PathSample& s) const {
  if (!z_) return;
  constexpr std::size_t z = hal::index(hal::Axis::z);
  s.position_mm[z] = static_cast<double>((*z_)[0]) * f::kPosition.scale;
  s.reference_mm[z] = static_cast<double>(static_cast<std::int64_t>((*z_)[0]) + (*z_)[1]) * f::kPosition.scale;
}

std::optional<fw::motion::PlanePoint> PathTelemetry::last_reference() const {
  if (samples_.empty()) return std::nullopt;
  return samples_.back().reference_mm;
}

}  // namespace tnv::can_host
