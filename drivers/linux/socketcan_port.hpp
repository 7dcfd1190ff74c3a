#pragma once
// The firmware's CAN controller on Linux SocketCAN (CAN_RAW), as a
// hal::CanPort for fw::can::CanNode:
// - receive filters for this node's identifiers and the broadcast node
//   (firmware/can/can_id.hpp: node id in the low 5 bits), standard frames;
// - CAN error frames are counted (by class), never returned;
// - transmit never blocks: a full socket queue drops the frame and counts
//   it (try_send -> timeout), so the tick thread cannot stall on the bus;
// - bus-off: the port stops writing (frames are dropped and counted) until
//   the controller reports CAN_ERR_RESTARTED (the kernel's restart-ms) or,
//   after `bus_off_holdoff`, a probe write goes through again.
// Both calls are bounded and allocation-free; the counters are atomics so
// another thread may read them while the tick thread runs.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "drivers/linux/socket_api.hpp"
#include "hal/can_port.hpp"

namespace tnv::drivers {

// SO_SNDBUF of the node's CAN socket: 1 byte asks for the kernel's minimum
// (SOCK_MIN_SNDBUF, about 4.6 KiB: a handful of CAN frames in flight).
inline constexpr int kSendBufferBytes = 1;

struct SocketCanPortOptions {
  std::string interface_name = "can0";
  std::uint8_t node_id = 1;
  Micros bus_off_holdoff{100'000};  // how long to stay quiet after bus-off before probing
  int max_reads_per_receive = 64;   // error frames skipped in one try_receive() at most
};

struct CanPortCounters {
  std::uint64_t rx_frames = 0;
  std::uint64_t rx_error_frames = 0;  // every CAN error frame
  std::uint64_t rx_short_reads = 0;   // reads shorter than a can_frame (discarded)
  std::uint64_t rx_failures = 0;      // read errors other than "nothing pending"
  std::uint64_t tx_frames = 0;
  std::uint64_t tx_dropped = 0;       // queue full, bus-off or a write error
  std::uint64_t bus_off_events = 0;
  std::uint64_t bus_off_recoveries = 0;
  std::uint64_t error_passive_events = 0;
};

// Node filter and broadcast filter: standard, non-remote frames whose low
// 6 identifier bits are `node` (resp. 0).
struct NodeFilters {
  can_filter node;
  can_filter broadcast;
};
NodeFilters node_filters(std::uint8_t node) noexcept;

class SocketCanPort final : public hal::CanPort {
 public:
  // Opens, filters and binds; nullptr with a one-line `error` naming the
  // interface and the failed step.
  static std::unique_ptr<SocketCanPort> open(SocketApi& api, const SocketCanPortOptions& options, std::string& error);
  ~SocketCanPort() override;
  SocketCanPort(const SocketCanPort&) = delete;
  SocketCanPort& operator=(const SocketCanPort&) = delete;

  hal::HalStatus try_send(const hal::CanFrame& frame) noexcept override;
  bool try_receive(hal::CanFrame& frame) noexcept override;
  std::uint64_t error_frames() const noexcept override { return rx_error_frames_.load(std::memory_order_relaxed); }

  CanPortCounters counters() const noexcept;
  bool bus_off() const noexcept { return bus_off_.load(std::memory_order_relaxed); }
  const std::string& interface_name() const noexcept { return options_.interface_name; }

 private:
  SocketCanPort(SocketApi& api, const SocketCanPortOptions& options, int fd) noexcept;
  void on_error_frame(const can_frame& raw) noexcept;
  static void add(std::atomic<std::uint64_t>& c) noexcept { c.fetch_add(1, std::memory_order_relaxed); }

  SocketApi& api_;
  SocketCanPortOptions options_;
  int fd_;
  std::atomic<bool> bus_off_{false};
  Micros bus_off_since_{0};
  std::atomic<std::uint64_t> rx_frames_{0}, rx_error_frames_{0}, rx_short_reads_{0}, rx_failures_{0};
  std::atomic<std::uint64_t> tx_frames_{0}, tx_dropped_{0};
  std::atomic<std::uint64_t> bus_off_events_{0}, bus_off_recoveries_{0}, error_passive_events_{0};
};

}  // namespace tnv::drivers
