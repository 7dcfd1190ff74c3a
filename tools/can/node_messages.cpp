#include "tools/can/node_messages.hpp"

#include <cctype>
#include <string>

namespace tnv::can_host {

namespace {

using can::field;
using can::message;
using can::MessageId;

constexpr const can::MessageDef& kParamRequest = message(MessageId::param_request);
constexpr const can::MessageDef& kParamReply = message(MessageId::param_reply);
constexpr const can::MessageDef& kCommand = message(MessageId::command);
constexpr const can::MessageDef& kCommandAck = message(MessageId::command_ack);
constexpr const can::MessageDef& kMove = message(MessageId::move);
constexpr const can::MessageDef& kCircle = message(MessageId::circle);
constexpr const can::MessageDef& kJog = message(MessageId::jog);
constexpr const can::MessageDef& kShaper = message(MessageId::shaper);
constexpr const can::MessageDef& kCaptureControl = message(MessageId::capture_control);
constexpr const can::MessageDef& kCaptureStatus = message(MessageId::capture_status);
constexpr const can::MessageDef& kCaptureData = message(MessageId::capture_data);
constexpr const can::MessageDef& kHeartbeat = message(MessageId::heartbeat);
constexpr const can::MessageDef& kFaultEvent = message(MessageId::fault_event);
constexpr const can::MessageDef& kEstop = message(MessageId::estop);

template <typename T>
T raw_as(const hal::CanFrame& frame, const can::FieldDef& f) {
  return static_cast<T>(can::read_raw(frame, f));
}

}  // namespace

hal::CanFrame param_request(std::uint8_t node, can::ParamOp op, std::uint16_t param, std::uint32_t value_raw) {
  hal::CanFrame f = can::make_frame(kParamRequest, node);
  can::write_raw(f, field(kParamRequest, "op"), static_cast<std::uint32_t>(op));
  can::write_raw(f, field(kParamRequest, "param"), param);
  can::write_raw(f, field(kParamRequest, "value"), value_raw);
  return f;
}

hal::CanFrame command_request(std::uint8_t node, can::CommandCode code, std::uint8_t axis, std::uint16_t arg,
                              double value) {
  hal::CanFrame f = can::make_frame(kCommand, node);
  can::write_raw(f, field(kCommand, "code"), static_cast<std::uint32_t>(code));
  can::write_raw(f, field(kCommand, "axis"), axis);
  can::write_raw(f, field(kCommand, "arg"), arg);
  can::write(f, field(kCommand, "value"), value);
  return f;
}

hal::CanFrame move_request(std::uint8_t node, std::uint8_t axis, double distance_mm, double speed_mm_s) {
  hal::CanFrame f = can::make_frame(kMove, node);
  can::write_raw(f, field(kMove, "axis"), axis);
  // The caller range-checks the speed (0.01 mm/s steps, at most 655.35 mm/s).
  can::write(f, field(kMove, "speed"), speed_mm_s);
  can::write(f, field(kMove, "distance"), distance_mm);
  return f;
}

hal::CanFrame circle_request(std::uint8_t node, double radius_mm, double feed_mm_s) {
  hal::CanFrame f = can::make_frame(kCircle, node);
  can::write(f, field(kCircle, "radius"), radius_mm);
  can::write(f, field(kCircle, "feed"), feed_mm_s);
  return f;
}

hal::CanFrame jog_request(std::uint8_t node, double speed_x_mm_s, double speed_y_mm_s) {
  hal::CanFrame f = can::make_frame(kJog, node);
  can::write(f, field(kJog, "speed_x"), speed_x_mm_s);
  can::write(f, field(kJog, "speed_y"), speed_y_mm_s);
  return f;
}

hal::CanFrame shaper_request(std::uint8_t node, std::uint8_t axis, std::uint8_t type, double freq_hz, double zeta) {
  hal::CanFrame f = can::make_frame(kShaper, node);
  can::write_raw(f, field(kShaper, "axis"), axis);
  can::write_raw(f, field(kShaper, "type"), type);
  can::write(f, field(kShaper, "zeta"), zeta);
  can::write(f, field(kShaper, "freq"), freq_hz);
  return f;
}

hal::CanFrame capture_request(std::uint8_t node, can::CaptureOp op, std::uint8_t frames, std::uint32_t offset) {
  hal::CanFrame f = can::make_frame(kCaptureControl, node);
  can::write_raw(f, field(kCaptureControl, "op"), static_cast<std::uint32_t>(op));
  can::write_raw(f, field(kCaptureControl, "frames"), frames);
  can::write_raw(f, field(kCaptureControl, "offset"), offset);
  return f;
}

hal::CanFrame estop_request(std::uint8_t node) { return can::make_frame(kEstop, node); }

Heartbeat read_heartbeat(const hal::CanFrame& frame) {
  Heartbeat h;
  h.state = raw_as<fw::MotionState>(frame, field(kHeartbeat, "state"));
  h.fault = raw_as<fw::FaultReason>(frame, field(kHeartbeat, "fault"));
  h.errors = raw_as<std::uint16_t>(frame, field(kHeartbeat, "errors"));
  h.overruns = raw_as<std::uint16_t>(frame, field(kHeartbeat, "overruns"));
  h.tick_low = raw_as<std::uint16_t>(frame, field(kHeartbeat, "tick_low"));
  return h;
}

CommandAck read_command_ack(const hal::CanFrame& frame) {
  CommandAck a;
  a.request = raw_as<std::uint8_t>(frame, field(kCommandAck, "request"));
  a.code = raw_as<std::uint8_t>(frame, field(kCommandAck, "code"));
  a.result = raw_as<can::ErrorCode>(frame, field(kCommandAck, "result"));
  a.state = raw_as<fw::MotionState>(frame, field(kCommandAck, "state"));
  a.fault = raw_as<fw::FaultReason>(frame, field(kCommandAck, "fault"));
  a.detail = raw_as<std::uint8_t>(frame, field(kCommandAck, "detail"));
  a.sequence = raw_as<std::uint16_t>(frame, field(kCommandAck, "sequence"));
  return a;
}

ParamReply read_param_reply(const hal::CanFrame& frame) {
  ParamReply r;
  r.op = raw_as<can::ParamOp>(frame, field(kParamReply, "op"));
  r.result = raw_as<can::ErrorCode>(frame, field(kParamReply, "result"));
  r.param = raw_as<std::uint16_t>(frame, field(kParamReply, "param"));
  r.value_raw = can::read_raw(frame, field(kParamReply, "value"));
  return r;
}

CaptureStatus read_capture_status(const hal::CanFrame& frame) {
  CaptureStatus s;
  s.state = raw_as<can::CaptureState>(frame, field(kCaptureStatus, "state"));
  s.result = raw_as<can::ErrorCode>(frame, field(kCaptureStatus, "result"));
  s.channels = raw_as<std::uint8_t>(frame, field(kCaptureStatus, "channels"));
  s.decimation = raw_as<std::uint8_t>(frame, field(kCaptureStatus, "decimation"));
  s.samples = can::read_raw(frame, field(kCaptureStatus, "samples"));
  return s;
}

CaptureData read_capture_data(const hal::CanFrame& frame) {
  CaptureData d;
  d.sequence = raw_as<std::uint8_t>(frame, field(kCaptureData, "sequence"));
  can::read_bytes(frame, field(kCaptureData, "data"), d.bytes);
  return d;
}

FaultEvent read_fault_event(const hal::CanFrame& frame) {
  FaultEvent e;
  e.reason = raw_as<fw::FaultReason>(frame, field(kFaultEvent, "reason"));
  e.axis = static_cast<std::int8_t>(can::read(frame, field(kFaultEvent, "axis")));
  e.tick_low = raw_as<std::uint16_t>(frame, field(kFaultEvent, "tick_low"));
  e.value = can::read(frame, field(kFaultEvent, "value"));
  return e;
}

std::string message_label(can::MessageId id) {
  const can::MessageDef* m = can::find_message(static_cast<std::uint8_t>(id));
  std::string out = m != nullptr ? m->name : "?";
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace tnv::can_host
