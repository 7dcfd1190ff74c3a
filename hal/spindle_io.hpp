#pragma once
#include <cstdint>

#include "hal/encoder_counter.hpp"

namespace tnv::hal {

// The spindle's channels on the I/O board, in the board's units, like the
// axes' (SpeedDacs, EncoderCounters, DiscreteIo): the speed DAC's code
// (offset binary, its sign is the direction), the drive's enable and
// direction outputs, and the spindle encoder's count and index latch as
// the tick's snapshot holds them. The setters stage; IoCycle::write_outputs
// sends them with the axes' outputs.
class SpindleIo {
 public:
  virtual ~SpindleIo() = default;
  virtual void set_spindle_code(std::uint16_t code) noexcept = 0;  // SpeedDacs::dac_bits() wide
  virtual void set_spindle_enable(bool enabled) noexcept = 0;
  // The drive's direction input (true: reverse, M4). The drive turns only
  // while it agrees with the code's sign; at 0 V either is fine.
  virtual void set_spindle_reverse(bool reverse) noexcept = 0;
  virtual std::uint32_t spindle_latched_count() const noexcept = 0;  // EncoderCounters::counter_bits() wide, wraps
  virtual IndexLatch spindle_index_latch() const noexcept = 0;        // once per revolution
};

}  // namespace tnv::hal
