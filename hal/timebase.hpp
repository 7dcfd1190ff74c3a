#pragma once
#include <cstdint>

namespace tnv::hal {

// What the board latched at the most recent control tick.
struct TickLatch {
  std::uint32_t clock_10mhz = 0;  // free-running 10 MHz counter at the tick (wraps every 429 s)
  std::uint32_t sequence = 0;     // tick sequence number (wraps)
  std::uint32_t read_clock_10mhz = 0;  // live counter when the snapshot was read (latency)
};

inline constexpr std::uint32_t kTimebaseHz = 10'000'000;

class Timebase {
 public:
  virtual ~Timebase() = default;
  virtual TickLatch latched_tick() const noexcept = 0;
};

}  // namespace tnv::hal
