#pragma once
// The FPGA I/O-board driver: implements hal::IoBoard over a RegisterBus with
// one batched read (the snapshot window) and one batched write (the output
// window) per tick, the LinuxCNC hostmot2 pattern. It cannot tell the real
// board from the emulated one.
#include <array>
#include <cstdint>

#include "hal/io_board.hpp"
#include "hal/io_board_registers.hpp"
#include "hal/register_bus.hpp"

namespace tnv::drivers {

struct FpgaBoardSettings {
  std::uint32_t tick_divider_clocks = hal::regs::kDefaultTickDivider;
  std::uint32_t watchdog_timeout_clocks = hal::regs::kDefaultWatchdogTimeout;
};

// Why init() failed, as static text (no allocation).
struct FpgaInitResult {
  hal::HalStatus status = hal::HalStatus::ok;
  const char* message = "";
  bool ok() const noexcept { return status == hal::HalStatus::ok; }
};

class FpgaIoBoard final : public hal::IoBoard {
 public:
  explicit FpgaIoBoard(hal::RegisterBus& bus) noexcept : bus_(bus) {}

  // Checks the board id and version (major equal, minor at least the map's),
  // programs the tick divider and watchdog, clears latched trips, and writes
  // safe outputs (DACs mid-scale, enables off, the spindle's too).
  FpgaInitResult init(const FpgaBoardSettings& settings) noexcept;

  // hal::IoCycle
  hal::HalStatus read_inputs() noexcept override;
  hal::HalStatus write_outputs() noexcept override;
  // hal::Timebase
  hal::TickLatch latched_tick() const noexcept override;
  // hal::EncoderCounters
  std::uint32_t latched_count(hal::Axis axis) const noexcept override;
  unsigned counter_bits() const noexcept override { return hal::regs::kEncoderBits; }
  hal::IndexLatch index_latch(hal::Axis axis) const noexcept override;
  // hal::SpeedDacs
  void set_code(hal::Axis axis, std::uint16_t code) noexcept override;
  unsigned dac_bits() const noexcept override { return hal::regs::kDacBits; }
  // hal::DiscreteIo
  hal::DiscreteInputs inputs() const noexcept override;
  void set_servo_enable(hal::Axis axis, bool enabled) noexcept override;
  // hal::AnalogInput
  std::uint16_t latched_force_code() const noexcept override;
  unsigned adc_bits() const noexcept override { return hal::regs::kAdcBits; }
  std::uint16_t latched_accel_code(hal::Axis axis) const noexcept override;
  // hal::Watchdog
  void kick() noexcept override { kick_pending_ = true; }
  // hal::SpindleIo
  void set_spindle_code(std::uint16_t code) noexcept override;
  void set_spindle_enable(bool enabled) noexcept override;
  void set_spindle_reverse(bool reverse) noexcept override;
  std::uint32_t spindle_latched_count() const noexcept override;
  hal::IndexLatch spindle_index_latch() const noexcept override;

  // The FAULTS word of the last snapshot (also mapped into inputs():
  // encoder_error, dac_error).
  std::uint32_t latched_fault_bits() const noexcept;
  // Clears the board's latches, the sticky FAULTS word and a watchdog trip
  // (CONTROL bits 1 and 0; the watchdog re-arms at the next kick), in one
  // bus write: the operator's reset between ticks, never part of the tick.
  // The next snapshot shows whether the cause is still there.
  hal::HalStatus clear_latched_faults() noexcept override;

 private:
  static constexpr std::uint16_t kMidCode = 1u << (hal::regs::kDacBits - 1);

  hal::RegisterBus& bus_;
  std::array<std::uint32_t, hal::regs::kSnapshotWords> snapshot_{};
  std::array<std::uint16_t, hal::kAxisCount> dac_codes_ = hal::per_axis(kMidCode);
  std::uint16_t spindle_code_ = kMidCode;
  std::uint32_t output_bits_ = 0;  // axis enables and the spindle's bits (OUTPUTS)
  bool kick_pending_ = false;
};

}  // namespace tnv::drivers
