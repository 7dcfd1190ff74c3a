#pragma once
#include <array>
#include <cstdint>

#include "hal/status.hpp"

namespace tnv::hal {

struct CanFrame {
  std::uint32_t id = 0;  // 11-bit standard identifier unless extended
  bool extended = false;
  std::uint8_t dlc = 0;  // 0..8
  std::array<std::uint8_t, 8> data{};
};

// Non-blocking CAN access; both calls are safe from the tick.
class CanPort {
 public:
  virtual ~CanPort() = default;
  virtual HalStatus try_send(const CanFrame& frame) noexcept = 0;  // timeout when the queue is full
  virtual bool try_receive(CanFrame& frame) noexcept = 0;          // false when nothing is pending
  // CAN error frames seen since start (bus errors, error-passive, bus-off);
  // 0 from a port that cannot see them. Reported in the heartbeat.
  virtual std::uint64_t error_frames() const noexcept { return 0; }
};

}  // namespace tnv::hal
