#include "tools/can/telemetry_view.hpp"

#include "tools/can/virtual_can_bus.hpp"

namespace tnv::can_host {

namespace {

using can::field;
using can::message;
using can::MessageId;

constexpr const can::MessageDef& kPosition = message(MessageId::tlm_position);
constexpr const can::MessageDef& kFollowing = message(MessageId::tlm_following);
constexpr const can::MessageDef& kSlidingX = message(MessageId::tlm_sliding_x);
constexpr const can::MessageDef& kSlidingY = message(MessageId::tlm_sliding_y);
constexpr const can::MessageDef& kOutput = message(MessageId::tlm_output);
constexpr const can::MessageDef& kContour = message(MessageId::tlm_contour);

void set_axis(std::optional<std::array<double, 2>>& slot, std::size_t axis, double v) {
  if (!slot) slot = std::array<double, 2>{0.0, 0.0};
  (*slot)[axis] = v;
}

}  // namespace

void TelemetryView::take(const hal::CanFrame& f, can::MessageId id) {
  ++frames;
  bits += VirtualCanBus::frame_bits(f);
  switch (id) {
    case MessageId::heartbeat: heartbeat = read_heartbeat(f); break;
    case MessageId::tlm_position:
      position_mm = {can::read(f, field(kPosition, "x")), can::read(f, field(kPosition, "y"))};
      break;
    case MessageId::tlm_following:
      following_mm = {can::read(f, field(kFollowing, "x")), can::read(f, field(kFollowing, "y"))};
      break;
    case MessageId::tlm_sliding_x:
      set_axis(s_mm_s, 0, can::read(f, field(kSlidingX, "s")));
      set_axis(d_hat_mm_s, 0, can::read(f, field(kSlidingX, "d_hat")));
      break;
    case MessageId::tlm_sliding_y:
      set_axis(s_mm_s, 1, can::read(f, field(kSlidingY, "s")));
      set_axis(d_hat_mm_s, 1, can::read(f, field(kSlidingY, "d_hat")));
      break;
    case MessageId::tlm_output:
      output = OutputTelemetry{{can::read(f, field(kOutput, "dac_x")), can::read(f, field(kOutput, "dac_y"))},
                               can::read(f, field(kOutput, "force"))};
      break;
    case MessageId::tlm_contour:
      contour = ContourTelemetry{can::read(f, field(kContour, "contour")), can::read(f, field(kContour, "motion_tick"))};
      break;
    default: break;
  }
}

}  // namespace tnv::can_host
