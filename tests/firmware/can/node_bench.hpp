#pragma once
// A CAN node on the scriptable fake board (no physics: the table stands
// still), for the protocol tests that need no motion beyond a dwell.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "firmware/can/can_node.hpp"
#include "firmware/can/param_table.hpp"
#include "tests/firmware/can/can_test_doubles.hpp"
#include "tests/firmware/fake_io_board.hpp"

namespace tnv::test {

inline constexpr std::uint8_t kNode = 1;

// A COMMAND_ACK's result and detail (the frame must be one).
inline fw::can::ErrorCode ack_result(const hal::CanFrame& r) {
  EXPECT_TRUE(is(r, fw::can::MessageId::command_ack));
  return static_cast<fw::can::ErrorCode>(raw_of(r, fw::can::MessageId::command_ack, "result"));
}
inline std::uint32_t ack_detail(const hal::CanFrame& r) { return raw_of(r, fw::can::MessageId::command_ack, "detail"); }

// Telemetry off, so a request's answer is the only frame; the table at
// (6, 0) (the default circle's start point) in the machine frame.
inline fw::can::NodeSettings quiet_settings() {
  static const fw::can::NodeSettings defaults = fw::can::default_node_settings();  // runs the PID tuning rule: once
  fw::can::NodeSettings s = defaults;
  s.firmware.axis[0].home_position_mm = 6.0;
  s.telemetry = {0, 0, 0, 0, 0, 0, 0};
  return s;
}

struct NodeBench {
  // `worker`: runs save/load (nullptr: inside service()).
  explicit NodeBench(const fw::can::NodeSettings& s = quiet_settings(), bool storage_fault = false,
                     hal::StorageWorker* worker = nullptr)
      : task(board, s.firmware),
        node(std::make_unique<fw::can::CanNode>(task, port, storage, s, storage_fault, nullptr, worker)) {
    step();  // the first tick reads home
    port.send(command(static_cast<std::uint8_t>(s.can.node_id), fw::can::CommandCode::take_ownership));  // the test host (kTestTag) commands
    node->service();
    port.drain();
  }
  // One tick, then the node's service().
  void step(int ticks = 1) {
    for (int i = 0; i < ticks; ++i) {
      board.next_tick();
      task.tick();
      node->service();
    }
  }
  // Sends one frame, services once (between two ticks) and returns what the node sent.
  std::vector<hal::CanFrame> request(const hal::CanFrame& f) {
    port.send(f);
    node->service();
    return port.drain();
  }
  // The single reply of a request (an empty frame with id 0x7FF if there was not exactly one).
  hal::CanFrame reply(const hal::CanFrame& f) {
    const std::vector<hal::CanFrame> out = request(f);
    if (out.size() != 1) return hal::CanFrame{0x7FF, false, 0, {}};
    return out[0];
  }
  double param(const char* name) const { return find(name).get(node->settings()); }
  static const fw::can::ParamDef& find(const char* name) { return *fw::can::find_param(name); }

  FakeIoBoard board;
  FakeCanPort port;
  MemoryStorage storage;
  fw::TickTask task;
  std::unique_ptr<fw::can::CanNode> node;
};

// Parameter id by name; the name must be in the table.
inline std::uint16_t id_of(const char* name) { return fw::can::find_param(name)->id; }

}  // namespace tnv::test
