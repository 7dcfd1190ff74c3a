// Fuzz entry: raw frames into the firmware node. Invariants: every frame
// the node sends is a well-formed to-host message of this node; a frame
// for another node (or extended) is ignored without a reply and changes
// nothing; a refused request changes no parameter; the live set always
// passes validate().
#include <memory>

#include "firmware/can/can_id.hpp"
#include "firmware/can/frame_codec.hpp"
#include "tests/firmware/can/node_bench.hpp"
#include "tests/fuzz/fuzz_entries.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace tnv::fuzz {

namespace can = fw::can;

namespace {

constexpr std::size_t kFrameRecordBytes = 12;

// The result a reply carries, ok for frames without one.
can::ErrorCode result_of(const hal::CanFrame& f) {
  using test::is;
  using test::raw_of;
  using can::MessageId;
  if (is(f, MessageId::command_ack)) return static_cast<can::ErrorCode>(raw_of(f, MessageId::command_ack, "result"));
  if (is(f, MessageId::param_reply)) return static_cast<can::ErrorCode>(raw_of(f, MessageId::param_reply, "result"));
  if (is(f, MessageId::capture_status))
    return static_cast<can::ErrorCode>(raw_of(f, MessageId::capture_status, "result"));
  return can::ErrorCode::ok;
}

}  // namespace

std::string can_frames(const std::uint8_t* data, std::size_t size) {
  auto bench = std::make_unique<test::NodeBench>();
  for (std::size_t r = 0; r + kFrameRecordBytes <= size; r += kFrameRecordBytes) {
    const std::uint8_t* rec = data + r;
    hal::CanFrame frame;
    frame.extended = (rec[0] & 1u) != 0;
    frame.id = static_cast<std::uint32_t>(rec[1] | rec[2] << 8) & (frame.extended ? 0xFFFFu : 0x7FFu);
    frame.dlc = static_cast<std::uint8_t>(rec[3] % 9u);
    for (std::size_t i = 0; i < 8; ++i) frame.data[i] = rec[4 + i];
    if ((rec[0] & 2u) != 0) {
      bench->step();
      bench->port.drain();
    }
    const std::vector<std::uint8_t> before = image_of(bench->node->settings());
    const can::NodeCounters was = bench->node->counters();
    const std::vector<hal::CanFrame> sent = bench->request(frame);
    const std::vector<std::uint8_t> after = image_of(bench->node->settings());
    const std::size_t at = r / kFrameRecordBytes;

    bool refused = false;
    for (const hal::CanFrame& f : sent) {
      const can::MessageDef* m = can::classify(f);
      if (m == nullptr || m->direction != can::Direction::from_node) return broken("the node sent an unknown frame", at);
      if (f.dlc != m->dlc) return broken("the node sent a frame with the wrong length", at);
      if (can::node_of(f.id) != test::kNode) return broken("the node sent a frame under another node id", at);
      refused = refused || result_of(f) != can::ErrorCode::ok;
    }
    const std::uint8_t node = can::node_of(frame.id);
    if (frame.extended || (node != test::kNode && node != can::kBroadcastNode)) {
      if (bench->node->counters().rx_ignored != was.rx_ignored + 1) return broken("a foreign frame was not ignored", at);
      if (!sent.empty()) return broken("a foreign frame was answered", at);
      if (before != after) return broken("a foreign frame changed a parameter", at);
    }
    if (refused && before != after) return broken("a refused request changed a parameter", at);
    if (!can::validate(bench->node->settings()).ok) return broken("the live set fails validate()", at);
  }
  return {};
}

}  // namespace tnv::fuzz
