// NodeTransmit: the priority queue, the per-service budget and the counts.
#include "firmware/can/node_transmit.hpp"

namespace tnv::fw::can {

void NodeTransmit::answer(const hal::CanFrame& frame, ErrorCode result) noexcept {
  ++sequence_;  // every answer passes here
  if (result != ErrorCode::ok) {
    ++counters_.requests_refused;
    if (result == ErrorCode::unknown_command) ++counters_.unknown_commands;
  }
  queue(frame, false);
}

bool NodeTransmit::send_now(const hal::CanFrame& frame) noexcept {
  if (budget_ <= 0 || can_.try_send(frame) != hal::HalStatus::ok) return false;
  --budget_;
  ++counters_.tx_frames;
  return true;
}

void NodeTransmit::dropped() noexcept {
  ++counters_.tx_dropped;
  dropped_since_heartbeat_ = true;
}

void NodeTransmit::queue(const hal::CanFrame& frame, bool droppable) noexcept {
  switch (tx_.push(frame, droppable)) {
    case TxPriorityQueue::Push::queued: return;
    case TxPriorityQueue::Push::evicted_other:  // only telemetry is ever evicted
      ++counters_.telemetry_dropped;
      dropped();
      return;
    case TxPriorityQueue::Push::dropped:
      if (droppable) ++counters_.telemetry_dropped;
      dropped();
      return;
  }
}

void NodeTransmit::flush() noexcept {
  while (!tx_.empty() && send_now(tx_.top())) tx_.pop();
}

}  // namespace tnv::fw::can
