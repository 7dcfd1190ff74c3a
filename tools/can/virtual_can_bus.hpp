#pragma once
// A classic CAN bus in simulated time, between the host and one emulated
// node: frames wait in each side's transmit queue, win arbitration by
// identifier (lowest first, among the frames queued when the bus goes
// idle), occupy the bus for their nominal length (47 + 8 x DLC bits for a
// standard frame, 111 bits with 8 data bytes, including the interframe
// space; stuff bits ignored) and reach the other side when they end. So no
// more frames are delivered per simulated millisecond than fit on the wire
// (9 at 1 Mbit/s).
#include <cstdint>
#include <deque>
#include <optional>

#include "hal/can_port.hpp"
#include "tools/can/host_bus.hpp"

namespace tnv::can_host {

enum class BusSide : std::uint8_t { host = 0, node = 1 };

struct VirtualCanBusOptions {
  std::uint32_t bitrate_bit_s = 1'000'000;
  std::size_t node_tx_capacity = 64;   // the node's transmit queue (CanPort::try_send fails when full)
  std::size_t node_rx_capacity = 64;   // the node's receive FIFO (overflow drops the frame)
  std::size_t host_rx_capacity = 65536;  // the host's socket buffer
};

struct VirtualBusCounters {
  std::uint64_t delivered_to_host = 0;
  std::uint64_t delivered_to_node = 0;
  std::uint64_t dropped_at_host = 0;  // host receive buffer full
  std::uint64_t dropped_at_node = 0;  // node receive FIFO full
  std::uint64_t busy_bits = 0;        // bits the bus was occupied, both directions
};

class VirtualCanBus {
 public:
  explicit VirtualCanBus(const VirtualCanBusOptions& options = {});

  // Queues a frame sent by `from` at time `now`. False when that side's
  // transmit queue is full (only the node's is bounded).
  bool enqueue(BusSide from, const hal::CanFrame& frame, Micros now);
  // Transmits every frame that completes by `until`.
  void advance_to(Micros until);
  // The next frame delivered to `to`, oldest first.
  std::optional<hal::CanFrame> take(BusSide to);

  std::size_t pending(BusSide from) const noexcept { return tx_[index(from)].size(); }
  const VirtualBusCounters& counters() const noexcept { return counters_; }
  std::uint32_t bitrate_bit_s() const noexcept { return options_.bitrate_bit_s; }

  // Nominal bits on the wire for one frame (without stuff bits).
  static std::uint32_t frame_bits(const hal::CanFrame& frame) noexcept;

 private:
  struct Pending {
    hal::CanFrame frame;
    Micros queued;
  };
  static std::size_t index(BusSide s) noexcept { return static_cast<std::size_t>(s); }
  Micros duration(const hal::CanFrame& frame) const noexcept;

  VirtualCanBusOptions options_;
  std::deque<Pending> tx_[2];
  std::deque<hal::CanFrame> rx_[2];
  Micros bus_free_at_{0};
  VirtualBusCounters counters_{};
};

}  // namespace tnv::can_host
