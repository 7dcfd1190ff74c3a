// Fuzz entry: raw frames and tick steps into the firmware node (its boring
// planner on). Invariants:
// every frame the node sends (answers and what it sends on its own between
// ticks) is a well-formed to-host message of this node; a frame for
// another node (or extended) is ignored: no answer (the rest of an upload
// under way may go out in the same service()), no parameter changed; a refused
// request changes no parameter and not what the boring planner learned (both
// are in the stored image compared); the live set always passes validate().
//
// Persistent: one node for the whole run, put back between inputs to a
// byte snapshot of its state after start-up (can_frames_node.hpp), so an
// input costs its frames and ticks, not a PID tuning or a task design.
#include <algorithm>

#include "firmware/can/can_id.hpp"
#include "firmware/can/frame_codec.hpp"
#include "tests/firmware/can/node_bench.hpp"
#include "tests/fuzz/can_frames_node.hpp"
#include "tests/fuzz/fuzz_entries.hpp"
#include "tests/fuzz/fuzz_support.hpp"
#include "tests/fuzz/settings_watch.hpp"

namespace tnv::fuzz {

namespace can = fw::can;

namespace {

// Ticks one input may run in all: enough to record a capture, get a
// circle past a short dwell and stop it; few enough that the run spends its
// time on many inputs rather than on long ones (the ticks are the largest
// part of an input's cost, about a third for 32-record inputs at 64 ticks).
// What only ends after hundreds of ticks (a default dwell, an excitation's
// settle, the jog dead-man) is left to the unit and HIL tests.
constexpr int kMaxTicksPerInput = 64;

// Telemetry off (test::quiet_settings) and the boring planner on, so BORE_GAUGE reaches it.
can::NodeSettings fuzz_settings() {
  can::NodeSettings s = test::quiet_settings();
  s.bore.enabled = true;
  return s;
}

CanFramesNode& fresh_node() {
  static CanFramesNode* const node = new CanFramesNode(fuzz_settings());  // lives for the whole run
  node->reset();
  return *node;
}

// The result a reply carries, ok for frames without one. The field
// definitions are looked up once: this runs for every frame the node sends.
can::ErrorCode result_of(const hal::CanFrame& f) {
  using can::MessageId;
  static const can::FieldDef& ack = test::fld(MessageId::command_ack, "result");
  static const can::FieldDef& param = test::fld(MessageId::param_reply, "result");
  static const can::FieldDef& capture = test::fld(MessageId::capture_status, "result");
  static const can::FieldDef& bore = test::fld(MessageId::bore_infeed, "result");
  const can::FieldDef* result = test::is(f, MessageId::command_ack)      ? &ack
                                : test::is(f, MessageId::param_reply)    ? &param
                                : test::is(f, MessageId::capture_status) ? &capture
                                : test::is(f, MessageId::bore_infeed)    ? &bore
                                                                         : nullptr;
  return result != nullptr ? static_cast<can::ErrorCode>(can::read_raw(f, *result)) : can::ErrorCode::ok;
}

// "" if every frame the node put on the port is a well-formed to-host
// message of this node; `refused` is set if one carries an error.
const char* check_sent(test::FakeCanPort& port, bool& refused) {
  hal::CanFrame f;
  refused = false;
  while (port.from_node.pop(f)) {
    const can::MessageDef* m = can::classify(f);
    if (m == nullptr || m->direction != can::Direction::from_node) return "the node sent an unknown frame";
    if (f.dlc != m->dlc) return "the node sent a frame with the wrong length";
    if (can::node_of(f.id) != test::kNode) return "the node sent a frame under another node id";
    refused = refused || result_of(f) != can::ErrorCode::ok;
  }
  return "";
}

// Ticks a record asks for before its frame: flags bit 1 on, bits 2..4 the
// count k: 2^k ticks, 1 .. 128.
int ticks_of(std::uint8_t flags) {
  if ((flags & 2u) == 0) return 0;
  return 1 << ((flags >> 2) & 7u);
}

}  // namespace

std::string can_frames(const std::uint8_t* data, std::size_t size) {
  CanFramesNode& b = fresh_node();
  static const SettingsWatch at_start = [&b] {
    SettingsWatch w;
    w.look(b.node.settings());
    return w;
  }();
  static SettingsWatch settings;  // its buffers live for the whole run
  settings = at_start;
  int ticks_left = kMaxTicksPerInput;
  for (std::size_t r = 0; r + kFrameRecordBytes <= size; r += kFrameRecordBytes) {
    const std::uint8_t* rec = data + r;
    const std::size_t at = r / kFrameRecordBytes;
    hal::CanFrame frame = frame_of_record(rec);
    if ((rec[0] & 0x20u) != 0 && !frame.extended) {
      // bit 5: message id (rec[1], 6 bits) addressed to this node, so mutations stay on the node's messages
      frame.id = can::make_can_id(static_cast<std::uint8_t>(rec[1] & can::kMessageIdMask), test::kNode);
    }

    bool refused = false;
    for (int t = std::min(ticks_of(rec[0]), ticks_left); t > 0; --t, --ticks_left) {
      b.board.next_tick();
      b.task.tick();
      b.node.service();
      if (const char* why = check_sent(b.port, refused); *why != '\0') return broken(why, at);
    }

    settings.look(b.node.settings());  // what the ticks changed is not the frame's doing
    const can::NodeCounters was = b.node.counters();
    const std::uint16_t answered = b.node.reply_sequence();
    b.port.send(frame);
    b.node.service();
    if (const char* why = check_sent(b.port, refused); *why != '\0') return broken(why, at);
    const bool changed = settings.look(b.node.settings());

    const std::uint8_t node = can::node_of(frame.id);
    if (frame.extended || (node != test::kNode && node != can::kBroadcastNode)) {
      if (b.node.counters().rx_ignored != was.rx_ignored + 1) return broken("a foreign frame was not ignored", at);
      // Frames may go out in the same service() (the rest of an upload under way, a reply queued
      // earlier): what must not happen is a new answer, which counts in the reply sequence.
      if (b.node.reply_sequence() != answered || b.node.counters().rx_frames != was.rx_frames)
        return broken("a foreign frame was answered", at);
      if (changed) return broken("a foreign frame changed a parameter", at);
    }
    if (refused && changed) return broken("a refused request changed a parameter", at);
    if (changed && !can::validate(b.node.settings()).ok) return broken("the live set fails validate()", at);
  }
  return {};
}

}  // namespace tnv::fuzz
