#pragma once
// A test host streaming program elements to the CAN rig (can_node_rig.hpp)
// frame by frame: SEGMENT (+ SEGMENT_TAIL) encoded as the real host does
// (firmware/can/segment_wire.hpp), each element's COMMAND_ACK read back.
#include <optional>
#include <string>
#include <vector>

#include "firmware/can/node_fields.hpp"
#include "firmware/can/request_tag.hpp"
#include "firmware/can/segment_wire.hpp"
#include "tests/hil/can_node_rig.hpp"
#include "tools/gcode/gcode_program.hpp"

namespace tnv::test {

struct ElementAck {
  std::uint32_t request = 0;  // message id answered (SEGMENT or SEGMENT_TAIL)
  std::uint32_t result = 255;
  std::uint32_t free_slots = 0;
  std::uint32_t detail = 0;
  std::uint32_t tag = 0;
};

inline ElementAck read_element_ack(const hal::CanFrame& f) {
  using fw::can::MessageId;
  return {raw_of(f, MessageId::command_ack, "request"), raw_of(f, MessageId::command_ack, "result"),
          raw_of(f, MessageId::command_ack, "code"), raw_of(f, MessageId::command_ack, "detail"),
          raw_of(f, MessageId::command_ack, "tag")};
}

class ProgramHost {
 public:
  ProgramHost(CanRig& rig, std::uint8_t host = 1) : rig_(rig), host_(host) {
    at_mm_ = rig.task().next_segment_start_mm();
  }

  // The frames of one element with this host's next tag; `at` is where the node's queue ends.
  fw::can::SegmentFrames frames(const fw::motion::Segment& s) {
    fw::can::SegmentFrames f;
    fw::can::encode_segment(s, at_mm_, kRigNode, fw::can::make_tag(host_, sequence_), f);
    sequence_ = static_cast<std::uint8_t>(sequence_ % 15 + 1);
    return f;
  }

  // Sends one element, services the node once, returns its acks (and keeps the other frames in `others`).
  std::vector<ElementAck> send(const fw::motion::Segment& s) {
    const fw::can::SegmentFrames f = frames(s);
    rig_.port.send(f.head);
    if (f.has_z) rig_.port.send(f.z);
    if (f.has_tail) rig_.port.send(f.tail);
    rig_.service();
    std::vector<ElementAck> acks = collect();
    if (acks.size() == 1 && acks[0].result == kOk) at_mm_ = f.end_mm;
    return acks;
  }
  // A manual tool change (SEGMENT kind tool_change) putting `tool` in the spindle, as run_gcode sends M6.
  std::vector<ElementAck> send_tool_change(int tool) {
    fw::can::SegmentFrames f;
    if (fw::can::encode_tool_change(tool, at_mm_, kRigNode, fw::can::make_tag(host_, sequence_), f) != nullptr) {
      // A tool the field cannot carry: sent as its raw bits, for the node to refuse.
      f.head = fw::can::make_frame(fw::can::fields::kSegmentMsg, kRigNode);
      fw::can::write_raw(f.head, fw::can::fields::kSegmentTag, fw::can::make_tag(host_, sequence_));
      fw::can::write_raw(f.head, fw::can::fields::kSegmentKind, static_cast<std::uint32_t>(fw::can::WireKind::tool_change));
      fw::can::write_raw(f.head, fw::can::fields::kSegmentX, static_cast<std::uint32_t>(tool) & 0xFFFFFFu);
    }
    sequence_ = static_cast<std::uint8_t>(sequence_ % 15 + 1);
    return send_frames({f.head});
  }
  std::vector<ElementAck> send_frames(const std::vector<hal::CanFrame>& frames) {
    for (const hal::CanFrame& f : frames) rig_.port.send(f);
    rig_.service();
    return collect();
  }
  std::vector<ElementAck> collect() {
    std::vector<ElementAck> acks;
    for (const hal::CanFrame& f : rig_.port.drain()) {
      if (is(f, fw::can::MessageId::command_ack)) acks.push_back(read_element_ack(f));
      else others.push_back(f);
    }
    return acks;
  }
  const fw::motion::PlanePoint& at_mm() const noexcept { return at_mm_; }

  std::vector<hal::CanFrame> others;  // PROGRAM_STATUS and the rest

 private:
  CanRig& rig_;
  std::uint8_t host_;
  std::uint8_t sequence_ = 1;
  fw::motion::PlanePoint at_mm_{};
};

// The result of the COMMAND_ACK a request brings (a PROGRAM_STATUS may come with it); 255: none.
inline std::uint32_t ack_result(CanRig& rig, const hal::CanFrame& request) {
  for (const hal::CanFrame& f : rig.request(request))
    if (is(f, fw::can::MessageId::command_ack)) return raw_of(f, fw::can::MessageId::command_ack, "result");
  return 255;
}

// The rig enabled and holding, the test host owning it.
inline std::unique_ptr<CanRig> holding_rig() {
  auto r = CanRig::make();
  if (!r) return nullptr;
  if (r->result(command(kRigNode, fw::can::CommandCode::enable)) != kOk) return nullptr;
  for (int k = 0; k < 5; ++k) r->step();
  r->port.drain();
  return r;
}

// A program in G91 (relative) moves, parsed from where the rig's table is held.
inline gcode::GcodeProgram relative_program(CanRig& rig, const std::string& text) {
  gcode::GcodeOptions o;
  o.start_mm = rig.task().next_segment_start_mm();
  gcode::GcodeResult r = gcode::parse_gcode(text, o);
  return r.program;
}

// 8 loops of line, counter-clockwise quarter, line, clockwise quarter: 32 elements, 10 mm/s.
inline std::string zigzag_arcs_text() {
  std::string text = "G17 G21 G91 F600\n";
  for (int i = 0; i < 8; ++i) text += "G1 X4\nG3 X3 Y3 I0 J3\nG1 Y4\nG2 X3 Y3 I3 J0\n";
  return text;
}

}  // namespace tnv::test
