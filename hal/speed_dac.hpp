#pragma once
#include <cstdint>

#include "hal/axis.hpp"

namespace tnv::hal {

// Speed-command DACs, offset binary: code 2^(bits-1) is 0 V.
class SpeedDacs {
 public:
  virtual ~SpeedDacs() = default;
  virtual void set_code(Axis axis, std::uint16_t code) noexcept = 0;
  virtual unsigned dac_bits() const noexcept = 0;
};

}  // namespace tnv::hal
