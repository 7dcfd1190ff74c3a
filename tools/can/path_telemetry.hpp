#pragma once
// Samples of a program run from the node's cyclic telemetry: TLM_POSITION
// (measured position) and TLM_FOLLOWING (reference - position) of the same
// tick. The node queues both every tick, but its transmit queue orders by
// identifier: when the bus is busy (a burst of SEGMENT frames wins every
// arbitration), the positions of several ticks leave before their
// followings. Each kind keeps its own order, so the n-th position pairs
// with the n-th following; counting starts at a position. The reference is
// rebuilt from the two rounded 1 nm values (within 1 nm).
#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "tools/can/node_messages.hpp"
#include "tools/score/path_score.hpp"

namespace tnv::can_host {

class PathTelemetry {
 public:
  void take(const hal::CanFrame& frame, can::MessageId id);
  const std::vector<hil::PathSample>& samples() const noexcept { return samples_; }
  // Frames still without a partner (one waits normally; more: the node dropped a TLM frame or
  // the two periods differ).
  std::uint64_t unpaired() const noexcept { return positions_.size() + followings_.size(); }
  // A HEARTBEAT said frames were dropped (its tx_dropped bit) while samples were taken: ticks are missing.
  bool dropped() const noexcept { return dropped_; }
  // The last reference seen (where the table is held when it rests).
  std::optional<fw::motion::PlanePoint> last_reference() const;

 private:
  std::deque<std::array<std::int32_t, 2>> positions_;
  std::deque<std::array<std::int32_t, 2>> followings_;
  std::vector<hil::PathSample> samples_;
  bool dropped_ = false;
};

}  // namespace tnv::can_host
