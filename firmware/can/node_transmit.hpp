#pragma once
// The CAN node's transmit side: every frame the node sends goes through the
// priority queue here (tx_priority_queue.hpp) and leaves in CAN-id order,
// at most kMaxTxPerService frames per service(). Telemetry is droppable and
// goes first when the queue is full; replies, events and the heartbeat are
// lost only when nothing droppable is left. Every answer to a request
// passes answer(), which counts it (the reply sequence, refusals).
//
// Bounded work, no allocation, exceptions, locks or logging: it runs in
// CanNode::service().
#include <cstddef>
#include <cstdint>

#include "firmware/can/protocol_enums.hpp"
#include "firmware/can/tx_priority_queue.hpp"
#include "hal/can_port.hpp"

namespace tnv::fw::can {

inline constexpr int kMaxTxPerService = 32;

struct TxCounters {
  std::uint64_t tx_frames = 0;
  std::uint64_t tx_dropped = 0;         // the queue was full (telemetry_dropped included)
  std::uint64_t telemetry_dropped = 0;  // telemetry frames dropped to make room (or for want of it)
  std::uint64_t requests_refused = 0;   // answers with a result other than ok
  std::uint64_t unknown_commands = 0;   // answers with unknown_command (malformed requests)
};

class NodeTransmit {
 public:
  explicit NodeTransmit(hal::CanPort& can) noexcept : can_(can) {}
  NodeTransmit(const NodeTransmit&) = delete;
  NodeTransmit& operator=(const NodeTransmit&) = delete;

  // A new service(): the budget of frames it may send.
  void begin_service() noexcept { budget_ = kMaxTxPerService; }
  // Into the priority queue; `droppable`: telemetry.
  void queue(const hal::CanFrame& frame, bool droppable) noexcept;
  // The answer to a request: counted, then queued (never dropped for telemetry's sake).
  void answer(const hal::CanFrame& frame, ErrorCode result) noexcept;
  // Straight to the port within the budget (a capture upload): false when not sent.
  bool send_now(const hal::CanFrame& frame) noexcept;
  // The queue into the port, in priority order, within the budget.
  void flush() noexcept;

  bool idle() const noexcept { return tx_.empty(); }  // nothing waits
  std::size_t pending() const noexcept { return tx_.size(); }
  // A frame was dropped since the last heartbeat (its kHbTxDropped bit).
  bool dropped_since_heartbeat() const noexcept { return dropped_since_heartbeat_; }
  void heartbeat_sent() noexcept { dropped_since_heartbeat_ = false; }
  const TxCounters& counters() const noexcept { return counters_; }
  std::uint16_t sequence() const noexcept { return sequence_; }  // requests answered, mod 65536

 private:
  void dropped() noexcept;

  hal::CanPort& can_;
  TxPriorityQueue tx_{};
  TxCounters counters_{};
  int budget_ = 0;                    // frames this service() may still send
  std::uint16_t sequence_ = 0;        // requests answered, mod 65536 (tests and the fuzz invariant)
  bool dropped_since_heartbeat_ = false;
};

}  // namespace tnv::fw::can
