#include "tools/can/node_messages.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "firmware/can/node_fields.hpp"

namespace tnv::can_host {

namespace {

using can::field;
using can::MessageId;

using can::fields::kParamRequestMsg;
using can::fields::kParamReplyMsg;
using can::fields::kCommandMsg;
using can::fields::kAckMsg;
using can::fields::kMoveMsg;
using can::fields::kCircleMsg;
using can::fields::kJogMsg;
using can::fields::kShaperMsg;
using can::fields::kExciteMsg;
using can::fields::kCaptureControlMsg;
using can::fields::kCaptureStatusMsg;
using can::fields::kCaptureDataMsg;
using can::fields::kHeartbeatMsg;
using can::fields::kFaultEventMsg;
using can::fields::kEstopMsg;
using can::fields::kProgramStatusMsg;

template <typename T>
T raw_as(const hal::CanFrame& frame, const can::FieldDef& f) {
  return static_cast<T>(can::read_raw(frame, f));
}

}  // namespace

hal::CanFrame param_request(std::uint8_t node, std::uint8_t tag, can::ParamOp op, std::uint16_t param,
                            std::uint32_t value_raw) {
  hal::CanFrame f = can::make_frame(kParamRequestMsg, node);
  can::write_raw(f, field(kParamRequestMsg, "tag"), tag);
  can::write_raw(f, field(kParamRequestMsg, "op"), static_cast<std::uint32_t>(op));
  can::write_raw(f, field(kParamRequestMsg, "param"), param);
  can::write_raw(f, field(kParamRequestMsg, "value"), value_raw);
  return f;
}

hal::CanFrame command_request(std::uint8_t node, std::uint8_t tag, can::CommandCode code, std::uint8_t axis,
                              std::uint8_t arg, double value) {
  hal::CanFrame f = can::make_frame(kCommandMsg, node);
  can::write_raw(f, field(kCommandMsg, "tag"), tag);
  can::write_raw(f, field(kCommandMsg, "code"), static_cast<std::uint32_t>(code));
  can::write_raw(f, field(kCommandMsg, "axis"), axis);
  can::write_raw(f, field(kCommandMsg, "arg"), arg);
  can::write(f, field(kCommandMsg, "value"), value);
  return f;
}

hal::CanFrame move_request(std::uint8_t node, std::uint8_t tag, std::uint8_t axis, double distance_mm,
                           double speed_mm_s) {
  hal::CanFrame f = can::make_frame(kMoveMsg, node);
  can::write_raw(f, field(kMoveMsg, "tag"), tag);
  can::write_raw(f, field(kMoveMsg, "axis"), axis);
  // The caller range-checks the speed (0.01 mm/s steps, at most 655.35 mm/s).
  can::write(f, field(kMoveMsg, "speed"), speed_mm_s);
  can::write(f, field(kMoveMsg, "distance"), distance_mm);
  return f;
}

hal::CanFrame spindle_request(std::uint8_t node, std::uint8_t tag, can::SpindleOp op, fw::SpindleDirection direction,
                              double rpm) {
  const can::MessageDef& m = can::fields::kSpindleMsg;
  hal::CanFrame f = can::make_frame(m, node);
  can::write_raw(f, field(m, "tag"), tag);
  can::write_raw(f, can::fields::kSpindleOp, static_cast<std::uint32_t>(op));
  can::write_raw(f, can::fields::kSpindleDirection, static_cast<std::uint32_t>(direction));
  can::write(f, can::fields::kSpindleRpm, rpm);
  return f;
}

hal::CanFrame circle_request(std::uint8_t node, std::uint8_t tag, double radius_mm, double feed_mm_s) {
  hal::CanFrame f = can::make_frame(kCircleMsg, node);
  can::write_raw(f, field(kCircleMsg, "tag"), tag);
  can::write(f, field(kCircleMsg, "radius"), radius_mm);
  can::write_saturated(f, field(kCircleMsg, "feed"), feed_mm_s);
  return f;
}

hal::CanFrame jog_request(std::uint8_t node, std::uint8_t tag, std::uint8_t axis, double speed_mm_s) {
  hal::CanFrame f = can::make_frame(kJogMsg, node);
  can::write_raw(f, field(kJogMsg, "tag"), tag);
  can::write_raw(f, field(kJogMsg, "axis"), axis);
  can::write_saturated(f, field(kJogMsg, "speed"), speed_mm_s);
  return f;
}

hal::CanFrame shaper_request(std::uint8_t node, std::uint8_t tag, std::uint8_t axis, std::uint8_t type,
                             double freq_hz, double zeta) {
  hal::CanFrame f = can::make_frame(kShaperMsg, node);
  can::write_raw(f, field(kShaperMsg, "tag"), tag);
  can::write_raw(f, field(kShaperMsg, "axis"), axis);
  can::write_raw(f, field(kShaperMsg, "type"), type);
  can::write_saturated(f, field(kShaperMsg, "zeta"), zeta);
  can::write_saturated(f, field(kShaperMsg, "freq"), freq_hz);
  return f;
}

hal::CanFrame excite_request(std::uint8_t node, std::uint8_t tag, std::uint8_t axis, std::uint8_t kind,
                             double level_mm_s, double duration_s) {
  hal::CanFrame f = can::make_frame(kExciteMsg, node);
  can::write_raw(f, field(kExciteMsg, "tag"), tag);
  can::write_raw(f, field(kExciteMsg, "axis"), axis);
  can::write_raw(f, field(kExciteMsg, "kind"), kind);
  // Out of the u16 range (or NaN): 0 s, which the node refuses as out of range.
  if (!can::write(f, field(kExciteMsg, "duration"), duration_s)) can::write_raw(f, field(kExciteMsg, "duration"), 0);
  can::write_saturated(f, field(kExciteMsg, "level"), level_mm_s);
  return f;
}

hal::CanFrame capture_request(std::uint8_t node, std::uint8_t tag, can::CaptureOp op, std::uint8_t frames,
                              std::uint32_t offset) {
  hal::CanFrame f = can::make_frame(kCaptureControlMsg, node);
  can::write_raw(f, field(kCaptureControlMsg, "tag"), tag);
  can::write_raw(f, field(kCaptureControlMsg, "op"), static_cast<std::uint32_t>(op));
  can::write_raw(f, field(kCaptureControlMsg, "frames"), frames);
  can::write_raw(f, field(kCaptureControlMsg, "offset"), offset);
  return f;
}

hal::CanFrame estop_request(std::uint8_t node) { return can::make_frame(kEstopMsg, node); }

ProgramStatus read_program_status(const hal::CanFrame& frame) {
  ProgramStatus p;
  p.state = raw_as<can::ProgramState>(frame, field(kProgramStatusMsg, "state"));
  p.free_slots = raw_as<std::uint8_t>(frame, field(kProgramStatusMsg, "free_slots"));
  p.underruns = raw_as<std::uint16_t>(frame, field(kProgramStatusMsg, "underruns"));
  p.element = raw_as<std::uint32_t>(frame, field(kProgramStatusMsg, "segment"));
  p.feed_override_percent = raw_as<std::uint8_t>(frame, field(kProgramStatusMsg, "feed_override"));
  return p;
}

ProgramTool read_program_tool(const hal::CanFrame& frame) {
  const double tool = can::read(frame, field(can::fields::kProgramToolMsg, "tool"));
  if (tool < 0.0) return {};
  return {true, static_cast<std::int32_t>(tool)};
}

std::string to_string(const ProgramTool& t) {
  if (!t.known) return "unknown";
  return t.tool == 0 ? "no tool" : "tool " + std::to_string(t.tool);
}

Heartbeat read_heartbeat(const hal::CanFrame& frame) {
  Heartbeat h;
  h.state = raw_as<fw::MotionState>(frame, field(kHeartbeatMsg, "state"));
  h.fault = raw_as<fw::FaultReason>(frame, field(kHeartbeatMsg, "fault"));
  h.errors = raw_as<std::uint16_t>(frame, field(kHeartbeatMsg, "errors"));
  h.overruns = raw_as<std::uint16_t>(frame, field(kHeartbeatMsg, "overruns"));
  h.free_slots = raw_as<std::uint8_t>(frame, field(kHeartbeatMsg, "free_slots"));
  h.owner = raw_as<std::uint8_t>(frame, field(kHeartbeatMsg, "owner"));
  h.axes = raw_as<std::uint8_t>(frame, field(kHeartbeatMsg, "axes"));
  return h;
}

CommandAck read_command_ack(const hal::CanFrame& frame) {
  CommandAck a;
  a.tag = raw_as<std::uint8_t>(frame, field(kAckMsg, "tag"));
  a.request = raw_as<std::uint8_t>(frame, field(kAckMsg, "request"));
  a.code = raw_as<std::uint8_t>(frame, field(kAckMsg, "code"));
  a.result = raw_as<can::ErrorCode>(frame, field(kAckMsg, "result"));
  a.state = raw_as<fw::MotionState>(frame, field(kAckMsg, "state"));
  a.fault = raw_as<fw::FaultReason>(frame, field(kAckMsg, "fault"));
  a.detail = raw_as<std::uint8_t>(frame, field(kAckMsg, "detail"));
  a.owner = raw_as<std::uint8_t>(frame, field(kAckMsg, "owner"));
  return a;
}

ParamReply read_param_reply(const hal::CanFrame& frame) {
  ParamReply r;
  r.tag = raw_as<std::uint8_t>(frame, field(kParamReplyMsg, "tag"));
  r.result = raw_as<can::ErrorCode>(frame, field(kParamReplyMsg, "result"));
  r.param = raw_as<std::uint16_t>(frame, field(kParamReplyMsg, "param"));
  r.value_raw = can::read_raw(frame, field(kParamReplyMsg, "value"));
  return r;
}

CaptureStatus read_capture_status(const hal::CanFrame& frame) {
  CaptureStatus s;
  s.tag = raw_as<std::uint8_t>(frame, field(kCaptureStatusMsg, "tag"));
  s.state = raw_as<can::CaptureState>(frame, field(kCaptureStatusMsg, "state"));
  s.result = raw_as<can::ErrorCode>(frame, field(kCaptureStatusMsg, "result"));
  s.channels = raw_as<std::uint8_t>(frame, field(kCaptureStatusMsg, "channels"));
  s.decimation = raw_as<std::uint8_t>(frame, field(kCaptureStatusMsg, "decimation"));
  s.samples = can::read_raw(frame, field(kCaptureStatusMsg, "samples"));
  return s;
}

CaptureData read_capture_data(const hal::CanFrame& frame) {
  CaptureData d;
  d.sequence = raw_as<std::uint8_t>(frame, field(kCaptureDataMsg, "sequence"));
  can::read_bytes(frame, field(kCaptureDataMsg, "data"), d.bytes);
  return d;
}

FaultEvent read_fault_event(const hal::CanFrame& frame) {
  FaultEvent e;
  e.reason = raw_as<fw::FaultReason>(frame, field(kFaultEventMsg, "reason"));
  e.axis = static_cast<std::int8_t>(can::read(frame, field(kFaultEventMsg, "axis")));
  e.tick_low = raw_as<std::uint16_t>(frame, field(kFaultEventMsg, "tick_low"));
  e.value = can::read(frame, field(kFaultEventMsg, "value"));
  return e;
}

std::string message_label(can::MessageId id) {
  const can::MessageDef* m = can::find_message(static_cast<std::uint8_t>(id));
  std::string out = m != nullptr ? m->name : "?";
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace tnv::can_host
