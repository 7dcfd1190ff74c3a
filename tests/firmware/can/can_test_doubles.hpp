#pragma once
// Test doubles for the CAN node: an in-memory CAN port (a fixed ring each
// way, no allocation, so it can sit inside the allocation-counting test),
// an in-memory parameter storage with failure injection, and frame
// builders / readers over the protocol table.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "firmware/can/can_id.hpp"
#include "firmware/can/frame_codec.hpp"
#include "firmware/can/param_image.hpp"
#include "firmware/can/protocol_messages.hpp"
#include "hal/can_port.hpp"
#include "hal/param_storage.hpp"

namespace tnv::test {

template <std::size_t N>
class FrameRing {
 public:
  bool push(const hal::CanFrame& f) noexcept {
    if (size_ == N) return false;
    frames_[(head_ + size_) % N] = f;
    ++size_;
    return true;
  }
  bool pop(hal::CanFrame& f) noexcept {
    if (size_ == 0) return false;
    f = frames_[head_];
    head_ = (head_ + 1) % N;
    --size_;
    return true;
  }
  std::size_t size() const noexcept { return size_; }
  void clear() noexcept { size_ = 0; }

 private:
  std::array<hal::CanFrame, N> frames_{};
  std::size_t head_ = 0;
  std::size_t size_ = 0;
};

// to_node: frames the host sent (the node receives them); from_node: what
// the node sent. tx_capacity limits how many frames the "bus" takes before
// the host drains them (0 = no limit up to the ring size).
class FakeCanPort final : public hal::CanPort {
 public:
  hal::HalStatus try_send(const hal::CanFrame& frame) noexcept override {
    if (tx_capacity != 0 && from_node.size() >= tx_capacity) return hal::HalStatus::timeout;
    return from_node.push(frame) ? hal::HalStatus::ok : hal::HalStatus::timeout;
  }
  bool try_receive(hal::CanFrame& frame) noexcept override { return to_node.pop(frame); }
  std::uint64_t error_frames() const noexcept override { return error_frame_count; }

  // Host side.
  void send(const hal::CanFrame& f) { to_node.push(f); }
  std::vector<hal::CanFrame> drain() {
    std::vector<hal::CanFrame> out;
    hal::CanFrame f;
    while (from_node.pop(f)) out.push_back(f);
    return out;
  }

  FrameRing<1024> to_node;
  FrameRing<8192> from_node;
  std::size_t tx_capacity = 0;
  std::uint64_t error_frame_count = 0;  // what the CAN controller reported
};

class MemoryStorage final : public hal::ParamStorage {
 public:
  hal::HalStatus write(std::span<const std::uint8_t> image) noexcept override {
    ++writes;
    if (fail_write) return hal::HalStatus::bus_error;
    bytes.assign(image.begin(), image.end());
    present = true;
    return hal::HalStatus::ok;
  }
  hal::HalStatus read(std::span<std::uint8_t> out, std::size_t& size) noexcept override {
    ++reads;
    if (fail_read) return hal::HalStatus::bus_error;
    if (!present) return hal::HalStatus::not_present;
    if (out.size() < bytes.size()) return hal::HalStatus::bad_address;
    for (std::size_t i = 0; i < bytes.size(); ++i) out[i] = bytes[i];
    size = bytes.size();
    return hal::HalStatus::ok;
  }

  std::vector<std::uint8_t> bytes;
  bool present = false;
  bool fail_write = false;
  bool fail_read = false;
  int writes = 0;
  int reads = 0;
};

// --- frames, host side

inline const fw::can::MessageDef& msg(fw::can::MessageId id) { return *fw::can::find_message(static_cast<std::uint8_t>(id)); }

inline const fw::can::FieldDef& fld(fw::can::MessageId id, const char* name) {
  for (const fw::can::FieldDef& f : msg(id).fields)
    if (std::string_view(f.name) == name) return f;
  return msg(id).fields[0];  // a test typo shows up as a wrong value
}

// The tag the test host puts in byte 0 of every tagged request: host 1, sequence 1.
inline constexpr std::uint8_t kTestTag = 0x11;

inline bool has_tag(const fw::can::MessageDef& m) {
  return !m.fields.empty() && std::string_view(m.fields[0].name) == "tag";
}

// An empty frame of message `id`; to-node messages with a tag carry kTestTag.
inline hal::CanFrame frame_to(fw::can::MessageId id, std::uint8_t node) {
  hal::CanFrame f = fw::can::make_frame(msg(id), node);
  if (msg(id).direction == fw::can::Direction::to_node && has_tag(msg(id))) f.data[0] = kTestTag;
  return f;
}
// The same frame from another host (tag = host << 4 | sequence).
inline hal::CanFrame with_tag(hal::CanFrame f, std::uint8_t tag) {
  f.data[0] = tag;
  return f;
}

inline void set_raw(hal::CanFrame& f, fw::can::MessageId id, const char* name, std::uint32_t raw) {
  fw::can::write_raw(f, fld(id, name), raw);
}
inline void set_value(hal::CanFrame& f, fw::can::MessageId id, const char* name, double v) {
  fw::can::write(f, fld(id, name), v);
}
inline std::uint32_t raw_of(const hal::CanFrame& f, fw::can::MessageId id, const char* name) {
  return fw::can::read_raw(f, fld(id, name));
}
inline double value_of(const hal::CanFrame& f, fw::can::MessageId id, const char* name) {
  return fw::can::read(f, fld(id, name));
}
inline bool is(const hal::CanFrame& f, fw::can::MessageId id) {
  return !f.extended && fw::can::message_of(f.id) == static_cast<std::uint8_t>(id);
}

inline hal::CanFrame param_request(std::uint8_t node, fw::can::ParamOp op, std::uint16_t id, std::uint32_t raw = 0) {
  using fw::can::MessageId;
  hal::CanFrame f = frame_to(MessageId::param_request, node);
  set_raw(f, MessageId::param_request, "op", static_cast<std::uint32_t>(op));
  set_raw(f, MessageId::param_request, "param", id);
  set_raw(f, MessageId::param_request, "value", raw);
  return f;
}
inline hal::CanFrame command(std::uint8_t node, fw::can::CommandCode code, std::uint8_t axis = 0, std::uint16_t arg = 0,
                             double value = 0.0) {
  using fw::can::MessageId;
  hal::CanFrame f = frame_to(MessageId::command, node);
  set_raw(f, MessageId::command, "code", static_cast<std::uint32_t>(code));
  set_raw(f, MessageId::command, "axis", axis);
  set_raw(f, MessageId::command, "arg", arg);
  set_value(f, MessageId::command, "value", value);
  return f;
}
inline hal::CanFrame capture_control(std::uint8_t node, fw::can::CaptureOp op, std::uint8_t frames = 0,
                                     std::uint32_t offset = 0) {
  using fw::can::MessageId;
  hal::CanFrame f = frame_to(MessageId::capture_control, node);
  set_raw(f, MessageId::capture_control, "op", static_cast<std::uint32_t>(op));
  set_raw(f, MessageId::capture_control, "frames", frames);
  set_raw(f, MessageId::capture_control, "offset", offset);
  return f;
}
inline hal::CanFrame circle(std::uint8_t node, double radius_mm, double feed_mm_s) {
  using fw::can::MessageId;
  hal::CanFrame f = frame_to(MessageId::circle, node);
  set_value(f, MessageId::circle, "radius", radius_mm);
  set_value(f, MessageId::circle, "feed", feed_mm_s);
  return f;
}
inline hal::CanFrame move(std::uint8_t node, std::uint8_t axis, double speed_mm_s, double distance_mm) {
  using fw::can::MessageId;
  hal::CanFrame f = frame_to(MessageId::move, node);
  set_raw(f, MessageId::move, "axis", axis);
  set_value(f, MessageId::move, "speed", speed_mm_s);
  set_value(f, MessageId::move, "distance", distance_mm);
  return f;
}
// JOG for one axis (the frame names it).
inline hal::CanFrame jog(std::uint8_t node, std::uint8_t axis, double speed_mm_s) {
  using fw::can::MessageId;
  hal::CanFrame f = frame_to(MessageId::jog, node);
  set_raw(f, MessageId::jog, "axis", axis);
  set_value(f, MessageId::jog, "speed", speed_mm_s);
  return f;
}

// The frames of one kind among `frames`.
inline std::vector<hal::CanFrame> only(const std::vector<hal::CanFrame>& frames, fw::can::MessageId id) {
  std::vector<hal::CanFrame> out;
  for (const hal::CanFrame& f : frames)
    if (is(f, id)) out.push_back(f);
  return out;
}

inline std::uint32_t f32_raw(float v) { return fw::can::float_bits(v); }

}  // namespace tnv::test
