#pragma once
#include <cstdint>

#include "hal/axis.hpp"

namespace tnv::hal {

// The board ADC channels, latched at the tick: the force sensor (unipolar
// code) and the tool-side accelerometers (offset-binary code, one per axis,
// scale hal::regs::kAccelFullScaleMmS2).
class AnalogInput {
 public:
  virtual ~AnalogInput() = default;
  virtual std::uint16_t latched_force_code() const noexcept = 0;
  virtual unsigned adc_bits() const noexcept = 0;
  virtual std::uint16_t latched_accel_code(Axis axis) const noexcept = 0;
};

}  // namespace tnv::hal
