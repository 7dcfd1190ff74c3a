#include "tools/can/node_client.hpp"

#include <algorithm>
#include <cstdio>

#include "hal/axis_choice.hpp"
#include "firmware/can/can_id.hpp"
#include "firmware/can/request_tag.hpp"
#include "tools/can/param_text.hpp"

namespace tnv::can_host {

namespace {

using can::MessageId;

std::string ms_text(Micros t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f ms", static_cast<double>(t.count()) / 1000.0);
  return buf;
}

bool in_motion(fw::MotionState s) { return s == fw::MotionState::dwell || s == fw::MotionState::moving; }

}  // namespace

NodeClient::NodeClient(HostBus& bus, std::uint8_t node, ClientOptions options)
    : bus_(bus), node_(node), options_(options) {}

std::uint8_t NodeClient::next_tag() {
  sequence_ = static_cast<std::uint8_t>((sequence_ + 1) & 0x0Fu);
  return can::make_tag(options_.host_id, sequence_);
}

namespace {

std::optional<std::uint8_t> reply_tag(const hal::CanFrame& frame, can::MessageId id) {
  switch (id) {
    case can::MessageId::command_ack: return read_command_ack(frame).tag;
    case can::MessageId::param_reply: return read_param_reply(frame).tag;
    case can::MessageId::capture_status: return read_capture_status(frame).tag;
    case can::MessageId::bore_infeed: return read_bore_infeed(frame).tag;
    default: return std::nullopt;
  }
}

}  // namespace

std::optional<can::MessageId> NodeClient::ours(const hal::CanFrame& frame) const {
  const can::MessageDef* m = can::classify(frame);
  if (m == nullptr || m->direction != can::Direction::from_node || can::node_of(frame.id) != node_) return std::nullopt;
  if (frame.dlc != m->dlc) return std::nullopt;  // a malformed frame is nobody's reply
  return static_cast<MessageId>(m->id);
}

void NodeClient::dispatch(const hal::CanFrame& frame, can::MessageId id) {
  if (id == MessageId::heartbeat) heartbeat_ = read_heartbeat(frame);
  if (id == MessageId::fault_event) fault_event_ = read_fault_event(frame);
  if (id == MessageId::program_status) program_status_ = read_program_status(frame);
  if (id == MessageId::program_tool) program_tool_ = read_program_tool(frame);
  if (listener_) listener_(frame, id);
}

std::optional<hal::CanFrame> NodeClient::wait_for(const Match& match, Micros deadline) {
  for (;;) {
    const Micros left = deadline - bus_.now();
    if (left <= Micros{0}) return std::nullopt;
    const std::optional<hal::CanFrame> frame = bus_.receive(left);
    if (!frame) continue;  // a signal or the deadline: the loop head decides
    const std::optional<MessageId> id = ours(*frame);
    if (!id) continue;
    dispatch(*frame, *id);
    if (match(*frame, *id)) return frame;
  }
}

std::string NodeClient::timeout_text(const std::string& what, can::MessageId reply, Micros waited) const {
  std::string out = "no ";
  out.append(message_label(reply)).append(" from node ").append(std::to_string(node_));
  out.append(" on ").append(bus_.describe()).append(" within ").append(ms_text(waited));
  out.append(" to '").append(what).append("'");
  return out;
}

hal::CanFrame NodeClient::transact(const hal::CanFrame& request, std::uint8_t tag, can::MessageId reply,
                                   const Match& match, const std::string& what) {
  bus_.send(request);
  const Micros deadline = bus_.now() + options_.timeout;
  const auto frame = wait_for(
      [&](const hal::CanFrame& f, MessageId id) {
        if (id != reply) return false;
        if (reply_tag(f, id) != tag) {
          ++replies_discarded_;  // a stale reply, or another host's
          return false;
        }
        return match(f, id);
      },
      deadline);
  if (!frame) throw RequestError(RequestError::Kind::timeout, timeout_text(what, reply, options_.timeout));
  return *frame;
}

// --- parameters

ParamReply NodeClient::param_op(can::ParamOp op, const can::ParamDef* p, std::uint32_t raw, const std::string& what) {
  const std::uint16_t id = p != nullptr ? p->id : 0;
  const std::uint8_t tag = next_tag();
  const hal::CanFrame f = transact(param_request(node_, tag, op, id, raw), tag, MessageId::param_reply,
                                   [&](const hal::CanFrame& frame, MessageId) {
                                     const ParamReply r = read_param_reply(frame);
                                     return p == nullptr || r.param == id || r.result != can::ErrorCode::ok;
                                   },
                                   what);
  const ParamReply r = read_param_reply(f);
  if (r.result != can::ErrorCode::ok) {
    std::string message = "node ";
    message.append(std::to_string(node_)).append(" refused '").append(what).append("': ");
    message += can::to_string(r.result);
    if (p != nullptr) {
      message.append(" (").append(p->name);
      if (r.result == can::ErrorCode::out_of_range) message.append(" range ").append(range_text(*p));
      if (r.result == can::ErrorCode::busy)
        message.append(" can only change at rest (apply: ").append(can::to_string(p->apply)).append(")");
      if (r.result != can::ErrorCode::unknown_id)
        message.append(", value now ").append(format_param_value(*p, can::from_wire(*p, r.value_raw)));
      message += ")";
    }
    if (r.result == can::ErrorCode::invalid && p == nullptr && r.value_raw != 0) {
      // A refused commit names the parameter the node blames in its value field.
      const can::ParamDef* blamed = can::find_param(static_cast<std::uint16_t>(r.value_raw));
      if (blamed != nullptr) message.append(" (").append(blamed->name).append(")");
    }
    if (r.result == can::ErrorCode::commissioning_required) {
      // A commit names the safety parameter in its value field.
      const can::ParamDef* blamed = p != nullptr ? p : can::find_param(static_cast<std::uint16_t>(r.value_raw));
      message.append(": ").append(blamed != nullptr ? blamed->name : "a parameter");
      message += " is a safety parameter: enter commissioning mode first";
    }
    throw RequestError(RequestError::Kind::refused, message, r.result);
  }
  return r;
}

void NodeClient::need_ownership() {
  if (owned_ || !options_.take_ownership_when_needed) return;
  take_ownership();
}

void NodeClient::release_ownership_if_taken() {
  if (owned_) release_ownership();
}

double NodeClient::get(const can::ParamDef& p) {
  const ParamReply r = param_op(can::ParamOp::get, &p, 0, std::string("get ") + p.name);
  return can::from_wire(p, r.value_raw);
}

double NodeClient::set(const can::ParamDef& p, double value) {
  std::string what = "set ";
  what.append(p.name).append(" = ").append(format_param_value(p, value));
  need_ownership();
  const ParamReply r = param_op(can::ParamOp::set, &p, can::to_wire(p, value), what);
  return can::from_wire(p, r.value_raw);
}

double NodeClient::stage(const can::ParamDef& p, double value) {
  std::string what = "stage ";
  what.append(p.name).append(" = ").append(format_param_value(p, value));
  const ParamReply r = param_op(can::ParamOp::stage, &p, can::to_wire(p, value), what);
  return can::from_wire(p, r.value_raw);
}

std::uint16_t NodeClient::commit() {
  need_ownership();
  return param_op(can::ParamOp::commit, nullptr, 0, "commit").param;
}

void NodeClient::discard() { param_op(can::ParamOp::discard, nullptr, 0, "discard"); }

// --- commands

CommandAck NodeClient::checked(const hal::CanFrame& request, std::uint8_t tag, std::uint8_t code,
                               const std::string& what) {
  const std::uint8_t request_id = can::message_of(request.id);
  const hal::CanFrame f = transact(request, tag, MessageId::command_ack,
                                   [&](const hal::CanFrame& frame, MessageId) {
                                     const CommandAck a = read_command_ack(frame);
                                     return a.request == request_id && a.code == code;
                                   },
                                   what);
  const CommandAck a = read_command_ack(f);
  if (a.result == can::ErrorCode::not_owner) owned_ = false;  // lost (host timeout) or never held
  if (a.result != can::ErrorCode::ok) {
    std::string message = "node ";
    message.append(std::to_string(node_)).append(" refused '").append(what).append("': ");
    message.append(can::to_string(a.result)).append(" (state ").append(fw::to_string(a.state));
    if (a.fault != fw::FaultReason::none) {
      message.append(", fault ").append(fw::to_string(a.fault));
      // The ack carries no axis; the node's FAULT_EVENT for the same reason does.
      if (fault_event_ && fault_event_->reason == a.fault && fault_event_->axis >= 0 && fault_event_->axis < 2)
        message.append(", axis ").append(hal::axis_label_or(fault_event_->axis, "?"));
    }
    if (a.detail != 0) message.append(", field ").append(std::to_string(a.detail));
    if (a.result == can::ErrorCode::not_owner) {
      message.append(", command ownership held by ");
      message.append(a.owner == 0 ? std::string("no host: take it first") : "host " + std::to_string(a.owner));
    }
    message += ")";
    throw RequestError(RequestError::Kind::refused, message, a.result);
  }
  return a;
}

CommandAck NodeClient::command(can::CommandCode code, std::uint8_t axis, std::uint8_t arg, double value) {
  const bool ownership = code == can::CommandCode::take_ownership || code == can::CommandCode::release_ownership;
  if (!ownership && code != can::CommandCode::program_status) need_ownership();  // a read, open to every host
  const std::uint8_t tag = next_tag();
  const CommandAck a = checked(command_request(node_, tag, code, axis, arg, value), tag,
                               static_cast<std::uint8_t>(code), can::to_string(code));
  if (ownership) owned_ = code == can::CommandCode::take_ownership;
  return a;
}

CommandAck NodeClient::move(std::uint8_t axis, double distance_mm, double speed_mm_s) {
  char what[96];
  std::snprintf(what, sizeof what, "move %s by %g mm at %g mm/s", hal::axis_label_or(axis, "?"), distance_mm, speed_mm_s);
  need_ownership();
  const std::uint8_t tag = next_tag();
  return checked(move_request(node_, tag, axis, distance_mm, speed_mm_s), tag, 0, what);
}

CommandAck NodeClient::circle(double radius_mm, double feed_mm_s) {
  char what[96];
  std::snprintf(what, sizeof what, "circle radius %g mm at %g mm/s", radius_mm, feed_mm_s);
  need_ownership();
  const std::uint8_t tag = next_tag();
  return checked(circle_request(node_, tag, radius_mm, feed_mm_s), tag, 0, what);
}

CommandAck NodeClient::spindle(can::SpindleOp op, fw::SpindleDirection direction, double rpm) {
  char what[96];
  if (op == can::SpindleOp::start)
    std::snprintf(what, sizeof what, "spindle start %s at %g rpm", fw::to_string(direction), rpm);
  else if (op == can::SpindleOp::speed)
    std::snprintf(what, sizeof what, "spindle speed %g rpm", rpm);
  else
    std::snprintf(what, sizeof what, "spindle stop");
  need_ownership();
  const std::uint8_t tag = next_tag();
  return checked(spindle_request(node_, tag, op, direction, rpm), tag, static_cast<std::uint8_t>(op), what);
}

CommandAck NodeClient::jog(std::uint8_t axis, double speed_mm_s) {
  char what[96];
  std::snprintf(what, sizeof what, "jog %s %g mm/s", hal::axis_label_or(axis, "?"), speed_mm_s);
  need_ownership();
  const std::uint8_t tag = next_tag();
  return checked(jog_request(node_, tag, axis, speed_mm_s), tag, 0, what);
}

CommandAck NodeClient::shaper(std::uint8_t axis, std::uint8_t type, double freq_hz, double zeta) {
  char what[96];
  std::snprintf(what, sizeof what, "shaper %s type %u at %g Hz, zeta %g", hal::axis_label_or(axis, "?"), type, freq_hz, zeta);
  need_ownership();
  const std::uint8_t tag = next_tag();
  return checked(shaper_request(node_, tag, axis, type, freq_hz, zeta), tag, 0, what);
}

CommandAck NodeClient::excite(std::uint8_t axis, std::uint8_t kind, double level_mm_s, double duration_s) {
  char what[96];
  std::snprintf(what, sizeof what, "excite %s: %s %g mm/s for %g s", hal::axis_label_or(axis, "?"),
                kind == 0 ? "step" : kind == 1 ? "ramp" : kind == 2 ? "sweep" : kind == 3 ? "multisine" : "kind?",
                level_mm_s, duration_s);
  need_ownership();
  const std::uint8_t tag = next_tag();
  return checked(excite_request(node_, tag, axis, kind, level_mm_s, duration_s), tag, 0, what);
}

void NodeClient::estop(bool broadcast) { bus_.send(estop_request(broadcast ? can::kBroadcastNode : node_)); }

// --- status

Heartbeat NodeClient::wait_heartbeat(Micros timeout) {
  const auto f = wait_for([](const hal::CanFrame&, MessageId id) { return id == MessageId::heartbeat; },
                          bus_.now() + timeout);
  if (!f) {
    std::string message = timeout_text("wait for status", MessageId::heartbeat, timeout);
    message += " (is tlm.heartbeat_ms 0?)";
    throw RequestError(RequestError::Kind::timeout, message);
  }
  return read_heartbeat(*f);
}

Heartbeat NodeClient::wait_at_rest(Micros timeout) {
  const auto f = wait_for(
      [](const hal::CanFrame& frame, MessageId id) {
        return id == MessageId::heartbeat && !in_motion(read_heartbeat(frame).state);
      },
      bus_.now() + timeout);
  if (!f) {
    std::string message = "node ";
    message.append(std::to_string(node_)).append(" still moving after ").append(ms_text(timeout));
    if (!heartbeat_) message += " (no HEARTBEAT seen: is tlm.heartbeat_ms 0?)";
    throw RequestError(RequestError::Kind::timeout, message);
  }
  return read_heartbeat(*f);
}

void NodeClient::pump(Micros duration) {
  wait_for([](const hal::CanFrame&, MessageId) { return false; }, bus_.now() + duration);
}

bool NodeClient::pump_until(const std::function<bool()>& done, Micros timeout) {
  if (done()) return true;
  return wait_for([&](const hal::CanFrame&, MessageId) { return done(); }, bus_.now() + timeout).has_value();
}

ProgramStatus NodeClient::program_status() {
  program_status_.reset();
  command(can::CommandCode::program_status);
  // PROGRAM_STATUS leaves the node in the same service as the ack, after it (higher identifier).
  if (!pump_until([this] { return program_status_.has_value(); }, options_.timeout))
    throw RequestError(RequestError::Kind::timeout, timeout_text("program status", MessageId::program_status, options_.timeout));
  return *program_status_;
}

ProgramTool NodeClient::program_tool() {
  program_tool_.reset();
  program_status();
  // PROGRAM_TOOL follows PROGRAM_STATUS in the same service.
  if (!pump_until([this] { return program_tool_.has_value(); }, options_.timeout))
    throw RequestError(RequestError::Kind::timeout, timeout_text("program tool", MessageId::program_tool, options_.timeout));
  return *program_tool_;
}

// --- capture

CaptureStatus NodeClient::capture(can::CaptureOp op) {
  const char* names[] = {"capture arm", "capture abort", "capture status", "capture upload"};
  const std::string what = names[static_cast<std::size_t>(op) % 4];
  const std::uint8_t tag = next_tag();
  const hal::CanFrame f = transact(capture_request(node_, tag, op, 0, 0), tag, MessageId::capture_status,
                                   [](const hal::CanFrame&, MessageId) { return true; }, what);
  const CaptureStatus s = read_capture_status(f);
  if (s.result != can::ErrorCode::ok) {
    std::string message = "node ";
    message.append(std::to_string(node_)).append(" refused '").append(what).append("': ");
    message += can::to_string(s.result);
    throw RequestError(RequestError::Kind::refused, message, s.result);
  }
  return s;
}

CaptureStatus NodeClient::wait_capture_done(Micros timeout, Micros poll_period) {
  const Micros deadline = bus_.now() + timeout;
  for (;;) {
    const CaptureStatus s = capture(can::CaptureOp::status);
    if (s.state == can::CaptureState::done) return s;
    if (bus_.now() >= deadline) {
      std::string message = "capture on node ";
      message.append(std::to_string(node_)).append(" not done after ").append(ms_text(timeout));
      message.append(" (state ").append(s.state == can::CaptureState::armed ? "armed: no trigger yet" : "recording");
      message += ")";
      throw RequestError(RequestError::Kind::timeout, message);
    }
    pump(std::min(poll_period, deadline - bus_.now()));
  }
}

std::vector<std::uint8_t> NodeClient::upload(const CaptureStatus& status, const UploadProgress& progress) {
  constexpr std::uint64_t kBytesPerFrame = 7;
  const std::uint64_t total = status.image_bytes();
  std::vector<std::uint8_t> image(total);
  std::uint64_t offset = 0;
  int stalls = 0;
  while (offset < total) {
    if (offset > 0xFFFFFFFFull) throw RequestError(RequestError::Kind::protocol, "capture image beyond 4 GiB");
    const std::uint64_t frames_left = (total - offset + kBytesPerFrame - 1) / kBytesPerFrame;
    const auto n = static_cast<std::uint8_t>(std::min<std::uint64_t>(options_.upload_block_frames, frames_left));
    const std::uint8_t tag = next_tag();
    bus_.send(capture_request(node_, tag, can::CaptureOp::upload, n, static_cast<std::uint32_t>(offset)));
    std::vector<bool> got(n, false);
    Micros deadline = bus_.now() + options_.timeout;
    for (;;) {
      const auto f = wait_for(
          [](const hal::CanFrame&, MessageId id) {
            return id == MessageId::capture_data || id == MessageId::capture_status;
          },
          deadline);
      if (!f) break;  // silent: whatever is missing is asked for again
      if (can::message_of(f->id) == static_cast<std::uint8_t>(MessageId::capture_status)) {
        const CaptureStatus s = read_capture_status(*f);
        if (s.tag != tag) {
          ++replies_discarded_;
          continue;
        }
        if (s.result == can::ErrorCode::ok) continue;
        std::string message = "node ";
        message.append(std::to_string(node_)).append(" refused 'capture upload' at byte ");
        message.append(std::to_string(offset)).append(": ").append(can::to_string(s.result));
        throw RequestError(RequestError::Kind::refused, message, s.result);
      }
      const CaptureData d = read_capture_data(*f);
      if (d.sequence >= n) continue;  // from an earlier block
      got[d.sequence] = true;
      const std::uint64_t at = offset + d.sequence * kBytesPerFrame;
      for (std::uint64_t i = 0; i < kBytesPerFrame && at + i < total; ++i) image[at + i] = d.bytes[i];
      deadline = bus_.now() + options_.timeout;
      if (d.sequence == n - 1) break;
    }
    const auto first_missing = static_cast<std::uint64_t>(std::find(got.begin(), got.end(), false) - got.begin());
    offset += first_missing * kBytesPerFrame;
    if (first_missing < n) {
      ++upload_rerequests_;
      stalls = first_missing == 0 ? stalls + 1 : 0;
      if (stalls > options_.upload_retries) {
        std::string message = "capture upload from node ";
        message.append(std::to_string(node_)).append(" stalled at byte ").append(std::to_string(offset));
        message.append(" of ").append(std::to_string(total)).append(" after ");
        message.append(std::to_string(stalls)).append(" re-requests");
        throw RequestError(RequestError::Kind::timeout, message);
      }
    } else {
      stalls = 0;
    }
    if (progress) progress(std::min(offset, total), total);
  }
  return image;
}

}  // namespace tnv::can_host
