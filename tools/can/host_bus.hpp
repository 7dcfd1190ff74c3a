#pragma once
// What the host needs from a CAN transport: send one frame, wait for the
// next one with a timeout, and the transport's clock. Two implementations:
// SocketCAN (socketcan_bus.hpp, wall time) and the in-process emulated
// controller (emulated_bus.hpp, simulated time: waiting advances ticks).
// The client (node_client.hpp) measures every timeout on now(), so it
// behaves the same on both.
#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>

#include "hal/can_port.hpp"

namespace tnv::can_host {

using Micros = std::chrono::microseconds;

// A transport failure (socket error, interface missing): not a refusal
// by the node, and not a timeout.
class BusError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Counters every transport keeps; what it cannot know stays 0.
struct BusCounters {
  std::uint64_t tx_frames = 0;
  std::uint64_t rx_frames = 0;
  std::uint64_t rx_error_frames = 0;  // CAN error frames reported by the controller
  std::uint64_t rx_short_reads = 0;   // reads that returned less than a whole frame (discarded)
  std::uint64_t rx_overflow = 0;      // frames lost because the host did not read them in time
};

class HostBus {
 public:
  virtual ~HostBus() = default;
  // Queues one frame; throws BusError when the transport fails or stays
  // full for longer than its send timeout.
  virtual void send(const hal::CanFrame& frame) = 0;
  // The next received frame, or nullopt when none came within `timeout`
  // (measured on now()). Throws BusError on a transport failure.
  virtual std::optional<hal::CanFrame> receive(Micros timeout) = 0;
  // Monotonic time of this transport (wall or simulated).
  virtual Micros now() = 0;
  // "can0", "emulated node (no-cut, seed 0)": for messages.
  virtual std::string describe() const = 0;
  virtual BusCounters counters() const = 0;
};

}  // namespace tnv::can_host
