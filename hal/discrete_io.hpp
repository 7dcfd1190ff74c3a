#pragma once
#include <array>

#include "hal/axis.hpp"

namespace tnv::hal {

// Digital inputs as latched at the tick; true = asserted (active),
// whatever the wiring polarity.
struct DiscreteInputs {
  bool estop = false;
  std::array<bool, kAxisCount> servo_alarm{};
  std::array<bool, kAxisCount> limit_positive{};
  std::array<bool, kAxisCount> limit_negative{};
  bool watchdog_tripped = false;  // board watchdog has forced outputs safe
};

class DiscreteIo {
 public:
  virtual ~DiscreteIo() = default;
  virtual DiscreteInputs inputs() const noexcept = 0;
  virtual void set_servo_enable(Axis axis, bool enabled) noexcept = 0;
};

}  // namespace tnv::hal
