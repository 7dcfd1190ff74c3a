#include "tools/can/telemetry_view.hpp"

#include "firmware/can/node_fields.hpp"
#include "tools/can/virtual_can_bus.hpp"

namespace tnv::can_host {

namespace {

using can::field;
using can::MessageId;

using can::fields::kPositionMsg;
using can::fields::kFollowingMsg;
using can::fields::kSlidingXMsg;
using can::fields::kSlidingYMsg;
using can::fields::kOutputMsg;
using can::fields::kContourMsg;
using can::fields::kArscMsg;

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
      position_mm = {can::read(f, field(kPositionMsg, "x")), can::read(f, field(kPositionMsg, "y"))};
      break;
    case MessageId::tlm_following:
      following_mm = {can::read(f, field(kFollowingMsg, "x")), can::read(f, field(kFollowingMsg, "y"))};
      break;
    case MessageId::tlm_sliding_x:
      set_axis(s_mm_s, 0, can::read(f, field(kSlidingXMsg, "s")));
      set_axis(d_hat_mm_s, 0, can::read(f, field(kSlidingXMsg, "d_hat")));
      break;
    case MessageId::tlm_sliding_y:
      set_axis(s_mm_s, 1, can::read(f, field(kSlidingYMsg, "s")));
      set_axis(d_hat_mm_s, 1, can::read(f, field(kSlidingYMsg, "d_hat")));
      break;
    case MessageId::tlm_output:
      output = OutputTelemetry{{can::read(f, field(kOutputMsg, "dac_x")), can::read(f, field(kOutputMsg, "dac_y"))},
                               can::read(f, field(kOutputMsg, "force"))};
      break;
    case MessageId::tlm_contour:
      contour = ContourTelemetry{can::read(f, field(kContourMsg, "contour")), can::read(f, field(kContourMsg, "motion_tick"))};
      break;
    case MessageId::tlm_arsc:
      arsc = ArscTelemetry{can::read(f, field(kArscMsg, "force")), can::read(f, field(kArscMsg, "force_ref")),
                           can::read(f, field(kArscMsg, "feed_override")),
                           can::read(f, field(kArscMsg, "cutting_gain"))};
      break;
    default: break;
  }
}

}  // namespace tnv::can_host
