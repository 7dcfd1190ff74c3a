#pragma once
// The emulated TNV-40: the FPGA I/O board at register level driving two
// table axes. The only door for firmware is read_register/write_register
// (through an emulated RegisterBus); truth() and the set_* inputs are the
// test bench's side of the machine.
#include <cstdint>
#include <memory>
#include <optional>

#include "emulator/scenario.hpp"
#include "hal/axis.hpp"

namespace tnv::emu {

// What really happened on one axis (judge side, not visible to firmware).
struct AxisTruth {
  double position_mm = 0.0;       // table position p
  double speed_mm_s = 0.0;        // table speed v
  double tool_position_mm = 0.0;  // p + structural-mode deflection
  double command_mm_s = 0.0;      // u actually applied (after DAC, enable, watchdog)
  double cutting_mm_s = 0.0;      // d_cut component on this axis
  bool stuck = false;             // Karnopp stick state
};

class Machine {
 public:
  explicit Machine(const Scenario& scenario);
  ~Machine();
  Machine(const Machine&) = delete;
  Machine& operator=(const Machine&) = delete;

  // --- register interface (what the bus sees); false = unmapped / read-only
  bool read_register(std::uint16_t word, std::uint32_t& value) noexcept;
  bool write_register(std::uint16_t word, std::uint32_t value) noexcept;

  // --- simulated time (sub-steps of 100 clocks = 10 us)
  void advance_to_next_tick() noexcept;               // returns right after the next tick latch
  void advance_clocks(std::uint64_t clocks) noexcept;  // rounded up to whole sub-steps
  std::uint64_t elapsed_clocks() const noexcept;
  double time_s() const noexcept;

  // --- judge side
  AxisTruth truth(hal::Axis axis) const noexcept;
  const Scenario& scenario() const noexcept;
  // S3 milling force on X (N) and the depth of cut now (mm); 0 / profile when [milling] is off.
  double milling_force_n() const noexcept;
  double milling_depth_mm() const noexcept;
  // First moment both servo enables were on (after the watchdog gate); the
  // commanded circle, which the cutting model follows, starts dwell_s later.
  std::optional<double> servo_on_time_s() const noexcept;
  std::optional<double> motion_start_s() const noexcept;

  // --- test-bench inputs
  void set_estop(bool asserted) noexcept;
  void set_servo_alarm(hal::Axis axis, bool asserted) noexcept;
  void set_limit(hal::Axis axis, bool positive_side, bool asserted) noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tnv::emu
