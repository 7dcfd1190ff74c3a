#pragma once
#include <array>

#include "hal/axis.hpp"
#include "hal/status.hpp"

namespace tnv::hal {

// Digital inputs and the board's own fault flags as latched at the tick;
// true = asserted (active), whatever the wiring polarity.
struct DiscreteInputs {
  bool estop = false;
  std::array<bool, kAxisCount> servo_alarm{};
  std::array<bool, kAxisCount> limit_positive{};
  std::array<bool, kAxisCount> limit_negative{};
  bool watchdog_tripped = false;  // board watchdog has forced outputs safe
  std::array<bool, kAxisCount> home_switch{};     // the axis' home switch is actuated
  // Sticky board faults (stay set until the board's fault latch is cleared):
  std::array<bool, kAxisCount> encoder_error{};  // the decoder saw an illegal A/B transition
  std::array<bool, kAxisCount> dac_error{};      // the DAC output readback differs from the code written
  bool probe = false;  // the touch probe is deflected (board 2.0)
};

class DiscreteIo {
 public:
  virtual ~DiscreteIo() = default;
  virtual DiscreteInputs inputs() const noexcept = 0;
  virtual void set_servo_enable(Axis axis, bool enabled) noexcept = 0;
  // Resets the board's sticky trips (encoder_error, dac_error, a watchdog
  // trip) on the operator's clear command, between ticks, never in one.
  // The next snapshot shows whether a cause is still there.
  virtual HalStatus clear_latched_faults() noexcept = 0;
};

}  // namespace tnv::hal
