#pragma once
#include <cstdint>

namespace tnv::hal {

// The force-sensor ADC channel, latched at the tick (unipolar code).
class AnalogInput {
 public:
  virtual ~AnalogInput() = default;
  virtual std::uint16_t latched_force_code() const noexcept = 0;
  virtual unsigned adc_bits() const noexcept = 0;
};

}  // namespace tnv::hal
