#pragma once
#include <cstdint>

#include "hal/axis.hpp"

namespace tnv::hal {

// x4 quadrature counters, latched at the tick. The raw value is a
// fixed-width counter that wraps; the firmware extends it by differences.
// The count latched at the encoder's index edge (once per motor
// revolution), as the tick's snapshot holds it: `edges` counts index edges
// modulo 256, so a change between snapshots says a new edge latched `count`.
struct IndexLatch {
  std::uint32_t count = 0;  // counter_bits() wide, like latched_count()
  std::uint8_t edges = 0;
};

class EncoderCounters {
 public:
  virtual ~EncoderCounters() = default;
  virtual std::uint32_t latched_count(Axis axis) const noexcept = 0;
  virtual unsigned counter_bits() const noexcept = 0;
  // A board without index inputs never reports an edge.
  virtual IndexLatch index_latch(Axis) const noexcept { return {}; }
};

}  // namespace tnv::hal
