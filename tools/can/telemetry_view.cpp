#include "tools/can/telemetry_view.hpp"

#include "firmware/can/node_fields.hpp"
#include "tools/can/virtual_can_bus.hpp"

namespace tnv::can_host {

namespace {

using can::field;
using can::MessageId;

using can::fields::kPositionMsg;
using can::fields::kFollowingMsg;
using can::fields::kOutputMsg;
using can::fields::kContourMsg;
using can::fields::kArscMsg;

void set_axis(std::optional<std::array<double, hal::kAxisCount>>& slot, std::size_t axis, double v) {
  if (!slot) slot = std::array<double, hal::kAxisCount>{};
  (*slot)[axis] = v;
}

// One value per axis from a frame's per-axis fields.
std::array<double, hal::kAxisCount> per_axis(const hal::CanFrame& f,
                                             const std::array<const can::FieldDef*, hal::kAxisCount>& fields) {
  std::array<double, hal::kAxisCount> out{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) out[i] = can::read(f, *fields[i]);
  return out;
}

}  // namespace

void TelemetryView::take(const hal::CanFrame& f, can::MessageId id) {
  ++frames;
  bits += VirtualCanBus::frame_bits(f);
  switch (id) {
    case MessageId::heartbeat: heartbeat = read_heartbeat(f); break;
    case MessageId::tlm_position: position_mm = per_axis(f, can::fields::kPositionFields); break;
    case MessageId::tlm_following: following_mm = per_axis(f, can::fields::kFollowingFields); break;
    case MessageId::tlm_output:
      output = OutputTelemetry{per_axis(f, can::fields::kOutputDacs), can::read(f, field(kOutputMsg, "force"))};
      break;
    case MessageId::tlm_contour:
      contour = ContourTelemetry{can::read(f, field(kContourMsg, "contour")), can::read(f, field(kContourMsg, "motion_tick"))};
      break;
    case MessageId::tlm_arsc:
      arsc = ArscTelemetry{can::read(f, field(kArscMsg, "force")), can::read(f, field(kArscMsg, "force_ref")),
                           can::read(f, field(kArscMsg, "feed_override")),
                           can::read(f, field(kArscMsg, "cutting_gain"))};
      break;
    default:
      // TLM_SLIDING_<axis>: one message per axis.
      for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
        if (static_cast<std::uint8_t>(id) != can::fields::kSlidingMsgs[i]->id) continue;
        set_axis(s_mm_s, i, can::read(f, can::fields::kSlidingS));
        set_axis(d_hat_mm_s, i, can::read(f, can::fields::kSlidingDHat));
      }
      break;
  }
}

}  // namespace tnv::can_host
