#pragma once
// Typed host-side views of the protocol messages: each request is built
// and each reply read through the table-driven frame codec
// (firmware/can/frame_codec.hpp), field by field, by name.
#include <array>
#include <cstdint>
#include <string>

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/param_table.hpp"
#include "firmware/can/program_tracker.hpp"
#include "firmware/spindle/spindle_control.hpp"
#include "firmware/supervisor/fault.hpp"
#include "firmware/tick/tick_record.hpp"

namespace tnv::can_host {

namespace can = tnv::fw::can;

struct Heartbeat {
  fw::MotionState state = fw::MotionState::disabled;
  fw::FaultReason fault = fw::FaultReason::none;
  std::uint16_t errors = 0;  // can::HeartbeatBit
  std::uint16_t overruns = 0;  // saturates at 255 (protocol 3)
  std::uint8_t free_slots = 0;  // motion queue (flow control for SEGMENT)
  std::uint8_t owner = 0;  // host id holding command ownership, 0 none
  std::uint8_t axes = 0;  // per-axis bits (can::hb_homed_bit, can::hb_shaper_bit)
  bool homed(hal::Axis a) const noexcept { return (axes & fw::can::hb_homed_bit(a)) != 0; }
  bool shaper_on(hal::Axis a) const noexcept { return (axes & fw::can::hb_shaper_bit(a)) != 0; }
};

struct ProgramStatus {
  fw::can::ProgramState state = fw::can::ProgramState::none;
  std::uint8_t free_slots = 0;
  std::uint16_t underruns = 0;  // of this program
  std::uint32_t element = 0;    // 1-based number of the element being run (acceptance order)
  std::uint8_t feed_override_percent = 100;
};

// PROGRAM_TOOL: the tool in the spindle as far as the node knows.
struct ProgramTool {
  bool known = false;     // false: unknown (since the node's start, or a tool change not confirmed)
  std::int32_t tool = 0;  // when known; 0 is no tool
  bool operator==(const ProgramTool&) const = default;
};
// "tool 3", "no tool", "unknown"
std::string to_string(const ProgramTool& tool);

struct CommandAck {
  std::uint8_t tag = 0;      // the request's tag, echoed
  std::uint8_t request = 0;  // message id acknowledged
  std::uint8_t code = 0;
  can::ErrorCode result = can::ErrorCode::ok;
  fw::MotionState state = fw::MotionState::disabled;
  fw::FaultReason fault = fw::FaultReason::none;
  std::uint8_t detail = 0;
  std::uint8_t owner = 0;  // host id holding command ownership after the request, 0 none
};

struct ParamReply {
  std::uint8_t tag = 0;
  can::ErrorCode result = can::ErrorCode::ok;
  std::uint16_t param = 0;
  std::uint32_t value_raw = 0;
};

struct CaptureStatus {
  std::uint8_t tag = 0;
  can::CaptureState state = can::CaptureState::idle;
  can::ErrorCode result = can::ErrorCode::ok;
  std::uint8_t channels = 0;
  std::uint8_t decimation = 0;
  std::uint32_t samples = 0;
  std::uint64_t image_bytes() const noexcept { return static_cast<std::uint64_t>(samples) * channels * 4u; }
};

struct CaptureData {
  std::uint8_t sequence = 0;
  std::array<std::uint8_t, 7> bytes{};
};

struct FaultEvent {
  fw::FaultReason reason = fw::FaultReason::none;
  std::int8_t axis = -1;
  std::uint16_t tick_low = 0;
  double value = 0.0;
};

// Requests (to node). `tag`: request_tag.hpp (host id << 4 | the host's sequence).
hal::CanFrame param_request(std::uint8_t node, std::uint8_t tag, can::ParamOp op, std::uint16_t param,
                            std::uint32_t value_raw);
hal::CanFrame command_request(std::uint8_t node, std::uint8_t tag, can::CommandCode code, std::uint8_t axis,
                              std::uint8_t arg, double value);
hal::CanFrame move_request(std::uint8_t node, std::uint8_t tag, std::uint8_t axis, double distance_mm,
                           double speed_mm_s);
// SPINDLE: start (direction, rpm), stop, speed (rpm); rpm as f32.
hal::CanFrame spindle_request(std::uint8_t node, std::uint8_t tag, can::SpindleOp op, fw::SpindleDirection direction,
                              double rpm);
// Feed in 0.01 mm/s steps (0 .. 655.35); the caller range-checks.
hal::CanFrame circle_request(std::uint8_t node, std::uint8_t tag, double radius_mm, double feed_mm_s);
// Speeds in 0.01 mm/s steps (+-327.67); out of range or NaN: the node refuses the clamped value.
hal::CanFrame jog_request(std::uint8_t node, std::uint8_t tag, std::uint8_t axis, double speed_mm_s);
// Frequency in 0.01 Hz steps (0 .. 655.35 Hz).
hal::CanFrame shaper_request(std::uint8_t node, std::uint8_t tag, std::uint8_t axis, std::uint8_t type,
                             double freq_hz, double zeta);
// EXCITE: kind 0 step, 1 ramp (duration rounded to 1 ms, level to 0.01 mm/s).
hal::CanFrame excite_request(std::uint8_t node, std::uint8_t tag, std::uint8_t axis, std::uint8_t kind,
                             double level_mm_s, double duration_s);
hal::CanFrame capture_request(std::uint8_t node, std::uint8_t tag, can::CaptureOp op, std::uint8_t frames,
                              std::uint32_t offset);
hal::CanFrame estop_request(std::uint8_t node);

// Replies (from node). Callers check the message id first (classify()).
Heartbeat read_heartbeat(const hal::CanFrame& frame);
CommandAck read_command_ack(const hal::CanFrame& frame);
ParamReply read_param_reply(const hal::CanFrame& frame);
CaptureStatus read_capture_status(const hal::CanFrame& frame);
CaptureData read_capture_data(const hal::CanFrame& frame);
FaultEvent read_fault_event(const hal::CanFrame& frame);
ProgramStatus read_program_status(const hal::CanFrame& frame);
ProgramTool read_program_tool(const hal::CanFrame& frame);

// Message name in upper case as the DBC spells it ("PARAM_REPLY").
std::string message_label(can::MessageId id);

}  // namespace tnv::can_host
