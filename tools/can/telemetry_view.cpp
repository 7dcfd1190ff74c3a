#include "tools/can/telemetry_view.hpp"

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "tools/can/virtual_can_bus.hpp"

namespace tnv::can_host {

namespace {

using can::field;
using can::MessageId;

using can::fields::kOutputMsg;
using can::fields::kContourMsg;
using can::fields::kArscMsg;

bool has(std::uint8_t flags, can::SpindleFlag bit) { return (flags & bit) != 0; }

SpindleTelemetry read_spindle(const hal::CanFrame& f) {
  namespace fl = can::fields;
  SpindleTelemetry s;
  s.target_rpm = can::read(f, fl::kTlmSpindleTarget);
  s.command_rpm = can::read(f, fl::kTlmSpindleCommand);
  s.measured_rpm = can::read(f, fl::kTlmSpindleMeasured);
  s.flags = static_cast<std::uint8_t>(can::read_raw(f, fl::kTlmSpindleFlags));
  // A cause this build does not know (a newer node) reads as none rather than past the list.
  const std::uint32_t cause = can::read_raw(f, fl::kTlmSpindleStopCause);
  if (cause < fw::kSpindleStopCauseCount) s.stop_cause = static_cast<fw::SpindleStopCause>(cause);
  return s;
}

void set_axis(std::optional<std::array<double, hal::kAxisCount>>& slot, std::size_t axis, double v) {
  if (!slot) slot = std::array<double, hal::kAxisCount>{};
  (*slot)[axis] = v;
}

}  // namespace

bool SpindleTelemetry::commanded_on() const noexcept { return has(flags, can::kSpindleOn); }
bool SpindleTelemetry::at_speed() const noexcept { return has(flags, can::kSpindleAtSpeed); }
bool SpindleTelemetry::inhibited() const noexcept { return has(flags, can::kSpindleInhibited); }
bool SpindleTelemetry::reverse() const noexcept { return has(flags, can::kSpindleReverse); }

const char* spindle_state(const SpindleTelemetry& s) noexcept {
  if (s.inhibited()) return "inhibited";
  if (s.commanded_on()) return s.at_speed() ? "at_speed" : "ramping";
  return has(s.flags, can::kSpindleEnabled) ? "stopping" : "off";
}

void TelemetryView::take(const hal::CanFrame& f, can::MessageId id) {
  ++frames;
  bits += VirtualCanBus::frame_bits(f);
  switch (id) {
    case MessageId::heartbeat: heartbeat = read_heartbeat(f); break;
    case MessageId::tlm_output:
      if (!output) output = OutputTelemetry{};
      output->force_n = can::read(f, field(kOutputMsg, "force"));
      break;
    case MessageId::tlm_contour:
      contour = ContourTelemetry{can::read(f, field(kContourMsg, "contour")), can::read(f, field(kContourMsg, "motion_tick"))};
      break;
    case MessageId::tlm_arsc:
      arsc = ArscTelemetry{can::read(f, field(kArscMsg, "force")), can::read(f, field(kArscMsg, "force_ref")),
                           can::read(f, field(kArscMsg, "feed_override")),
                           can::read(f, field(kArscMsg, "cutting_gain"))};
      break;
    case MessageId::tlm_spindle: spindle = read_spindle(f); break;
    case MessageId::program_tool: program_tool = read_program_tool(f); break;
    default: {
      // The per-axis messages: one per axis of each block.
      namespace fl = can::fields;
      const auto m = static_cast<std::uint8_t>(id);
      if (const auto a = fl::axis_of(fl::kPositionMsgs, m)) {
        set_axis(position_mm, hal::index(*a), can::read(f, fl::kPosition));
        set_axis(following_mm, hal::index(*a), can::read(f, fl::kFollowing));
      } else if (const auto c = fl::axis_of(fl::kSlidingMsgs, m)) {
        set_axis(s_mm_s, hal::index(*c), can::read(f, fl::kSlidingS));
        set_axis(d_hat_mm_s, hal::index(*c), can::read(f, fl::kSlidingDHat));
      } else if (const auto d = fl::axis_of(fl::kDacMsgs, m)) {
        if (!output) output = OutputTelemetry{};
        output->dac_code[hal::index(*d)] = can::read(f, fl::kDacCode);
      }
      break;
    }
  }
}

}  // namespace tnv::can_host
