#pragma once
// The node the can_frames entry feeds: the node, its task and the doubles,
// built once for the whole run, and put back between inputs to the state
// right after start-up (first tick read, the test host owning commands).
//
// The reset writes back a byte snapshot of the board, the task and the
// node taken after that start-up: no constructor runs again, so an input
// costs its frames and ticks, not the task's shaper and ARSC design, the
// validation of the whole set or the zeroing of the 512 KiB capture buffer
// (together most of an input's time before). The task and the node own no
// heap memory and point only at each other, the doubles and the defaults
// computed once, all of which stay where they are. The capture buffer is
// left out of the snapshot: the recorder reads back only words recorded
// since its last arm (image_byte() is 0 past the image), so old words
// cannot reach an input's behaviour.
#include <cstddef>
#include <cstdint>

#include "firmware/can/can_node.hpp"
#include "tests/firmware/can/node_bench.hpp"
#include "tests/fuzz/byte_snapshot.hpp"

namespace tnv::fuzz {

class CanFramesNode {
 public:
  explicit CanFramesNode(const fw::can::NodeSettings& s) : task(board, s.firmware), node(task, port, storage, s) {
    board.next_tick();  // the first tick reads home (as test::NodeBench does)
    task.tick();
    node.service();
    // the test host (kTestTag) holds command ownership, as on test::NodeBench
    port.to_node.push(test::command(test::kNode, fw::can::CommandCode::take_ownership));
    node.service();
    port.from_node.clear();
    board_at_start_ = board;
    task_at_start_.save(&task, sizeof task);
    node_at_start_.save(&node, bytes_before_capture_buffer());
  }
  CanFramesNode(const CanFramesNode&) = delete;
  CanFramesNode& operator=(const CanFramesNode&) = delete;

  // Back to the state right after the constructor; the doubles emptied.
  void reset() {
    board = board_at_start_;
    task_at_start_.restore();
    node_at_start_.restore();
    port.to_node.clear();
    port.from_node.clear();
    port.error_frame_count = 0;
    storage.bytes.clear();  // keeps its capacity: no allocation per input
    storage.present = false;
    storage.writes = 0;
    storage.reads = 0;
  }

  test::FakeIoBoard board;
  test::FakeCanPort port;
  test::MemoryStorage storage;
  fw::TickTask task;
  fw::can::CanNode node;

 private:
  // The node's bytes up to its capture buffer, which can_node.hpp keeps
  // last; the whole node should that ever change.
  std::size_t bytes_before_capture_buffer() const {
    const auto* first = reinterpret_cast<const unsigned char*>(&node);
    const auto* buffer = reinterpret_cast<const unsigned char*>(node.capture_words().data());
    const auto before = static_cast<std::size_t>(buffer - first);
    const bool last = before + sizeof(std::uint32_t) * fw::can::kCaptureCapacityWords == sizeof node;
    return last ? before : sizeof node;
  }

  test::FakeIoBoard board_at_start_;
  ByteSnapshot task_at_start_;
  ByteSnapshot node_at_start_;
};

}  // namespace tnv::fuzz
