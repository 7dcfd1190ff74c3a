#pragma once
// Everything the tick touches on the I/O board. read_inputs() latches one
// snapshot (one batched bus read); the getters return that snapshot; the
// setters stage outputs that write_outputs() sends in one batched write.
#include "hal/analog_input.hpp"
#include "hal/discrete_io.hpp"
#include "hal/encoder_counter.hpp"
#include "hal/speed_dac.hpp"
#include "hal/spindle_io.hpp"
#include "hal/status.hpp"
#include "hal/timebase.hpp"
#include "hal/watchdog.hpp"

namespace tnv::hal {

class IoCycle {
 public:
  virtual ~IoCycle() = default;
  virtual HalStatus read_inputs() noexcept = 0;
  virtual HalStatus write_outputs() noexcept = 0;
};

class IoBoard : public IoCycle,
                public Timebase,
                public EncoderCounters,
                public SpeedDacs,
                public DiscreteIo,
                public AnalogInput,
                public Watchdog,
                public SpindleIo {};

}  // namespace tnv::hal
