#pragma once
#include <cstdint>

#include "hal/axis.hpp"

namespace tnv::hal {

// x4 quadrature counters, latched at the tick. The raw value is a
// fixed-width counter that wraps; the firmware extends it by differences.
class EncoderCounters {
 public:
  virtual ~EncoderCounters() = default;
  virtual std::uint32_t latched_count(Axis axis) const noexcept = 0;
  virtual unsigned counter_bits() const noexcept = 0;
};

}  // namespace tnv::hal
