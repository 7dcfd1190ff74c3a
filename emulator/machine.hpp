#pragma once
// The emulated TNV-40: the FPGA I/O board at register level driving the
// axes of the list (the XY table and the Z head: z_axis_plant.hpp) and the
// spindle. The only door for firmware is read_register/write_register
// (through an emulated RegisterBus); truth() and the set_* inputs are the
// test bench's side of the machine. The scenario's fault schedule
// (fault_schedule.hpp) is injected as simulated time passes: a read during
// an injected bus error returns false; a missed tick makes
// advance_to_next_tick() sleep through that many tick latches.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>

#include "emulator/scenario.hpp"
#include "hal/axis.hpp"

namespace tnv::emu {

class BoringPass;
class CuttingAtTool;

// What really happened on one axis (judge side, not visible to firmware).
struct AxisTruth {
  double position_mm = 0.0;       // table position: the motor side through the ball screw (backlash, lead error)
  double speed_mm_s = 0.0;        // speed v of the motor side (the table's too, but while the lash is taken up)
  double tool_position_mm = 0.0;  // table + structural-mode deflection
  double motor_position_mm = 0.0; // plant state p: the motor side in mm of screw travel, what the encoder counts
  double command_mm_s = 0.0;      // u actually applied (after DAC, enable, watchdog)
  double cutting_mm_s = 0.0;      // d_cut component on this axis (with [stock]: and the force where the tool is)
  bool stuck = false;             // Karnopp stick state
  std::uint32_t dac_output_code = 0;  // what the DAC outputs (its register's code unless a fault sticks it)
};

// What the spindle really does (judge side).
struct SpindleTruth {
  double speed_rpm = 0.0;         // signed: negative is reverse
  double revolutions = 0.0;       // turned since power-up, signed
  double command_rpm = 0.0;       // what the drive follows (0 when disabled or the direction input disagrees)
  bool at_rest = true;            // no command and stopped: not integrated
};

// The board's output side now (judge side: readable whatever the bus does).
struct BoardOutputs {
  std::array<std::uint32_t, hal::kAxisCount> dac_register{};  // each axis' DAC register as last written
  std::array<std::uint32_t, hal::kAxisCount> dac_output{};    // what the DACs output (differs when stuck)
  std::array<bool, hal::kAxisCount> enabled{};                // servo enable reaching the drive (watchdog gated)
  bool watchdog_tripped = false;
  std::optional<double> watchdog_trip_s;                      // machine time of the most recent trip
  std::uint32_t spindle_dac_register = 0;                     // DAC_SPINDLE as last written
  std::uint32_t spindle_dac_mid_code = 0;                     // its 0 V ([spindle] dac_bits)
  bool spindle_enabled = false;                               // its enable reaching the drive (watchdog gated)
  // DAC registers at mid-scale and every enable off, the spindle's too.
  bool safe(std::uint32_t mid_code) const noexcept {
    for (std::size_t i = 0; i < hal::kAxisCount; ++i)
      if (enabled[i] || dac_register[i] != mid_code) return false;
    return !spindle_enabled && spindle_dac_register == spindle_dac_mid_code;
  }
};

class Machine {
 public:
  explicit Machine(const Scenario& scenario);
  ~Machine();
  Machine(const Machine&) = delete;
  Machine& operator=(const Machine&) = delete;

  // --- register interface (what the bus sees); false = unmapped / read-only,
  // or any read while an injected bus_read_error is active
  bool read_register(std::uint16_t word, std::uint32_t& value) noexcept;
  bool write_register(std::uint16_t word, std::uint32_t value) noexcept;
  // Consecutive registers from first_word, all or nothing: false (and no
  // register changed) when any word is unmapped, read-only or refuses its
  // value, as a bad request must change nothing.
  bool write_registers(std::uint16_t first_word, std::span<const std::uint32_t> values) noexcept;
  // Consecutive registers from first_word, each as read_register reads it;
  // false at the first word that fails (the words before it are read).
  bool read_registers(std::uint16_t first_word, std::span<std::uint32_t> values) noexcept;

  // --- simulated time (sub-steps of 100 clocks = 10 us)
  void advance_to_next_tick() noexcept;               // returns right after the next tick latch the firmware wakes for
  void advance_clocks(std::uint64_t clocks) noexcept;  // rounded up to whole sub-steps
  std::uint64_t elapsed_clocks() const noexcept;
  double time_s() const noexcept;
  // [io]: the firmware's work this tick, between its snapshot read and its
  // output write, in board time (the HIL rig's metered charge); moves the
  // landing of the output write issued since the last latch. Without [io]
  // outputs land at once and this does nothing.
  void set_firmware_work_ns(double work_ns) noexcept;

  // --- judge side
  AxisTruth truth(hal::Axis axis) const noexcept;
  SpindleTruth spindle_truth() const noexcept;
  BoardOutputs board_outputs() const noexcept;
  std::uint32_t dac_mid_code() const noexcept;
  // Motor-side position of an encoder index mark (marks repeat every lead):
  // the reference a homing cycle's home is taken from.
  double index_mark_mm(hal::Axis axis) const noexcept;
  const Scenario& scenario() const noexcept;
  // S3 milling force on X (N) and the depth of cut now (mm); 0 / profile when [milling] is off.
  double milling_force_n() const noexcept;
  double milling_depth_mm() const noexcept;
  // [stock] on: the process where the tool is (its force, a_p, the crash
  // log); nullptr without a stock.
  const CuttingAtTool* cutting_at_tool() const noexcept;
  // [boring] on (with [stock]): the boring bar where the tool is, stepped
  // with the tool's process (boring_pass.hpp); the bench starts each part
  // and reads the gauge after it. nullptr otherwise.
  BoringPass* boring_pass() noexcept;
  const BoringPass* boring_pass() const noexcept;

  // --- test-bench inputs
  void set_estop(bool asserted) noexcept;
  void set_servo_alarm(hal::Axis axis, bool asserted) noexcept;
  void set_limit(hal::Axis axis, bool positive_side, bool asserted) noexcept;

  // --- fault schedule (judge side): is scenario().faults[i] in effect now?
  // One-shot kinds (encoder_illegal, missed_tick, late_tick) stay "in
  // effect" from their start on.
  bool fault_active(std::size_t i) const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tnv::emu
