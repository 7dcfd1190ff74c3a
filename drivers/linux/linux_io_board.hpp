#pragma once
// The I/O board as the firmware sees it on a Linux board: the FPGA board
// (registers over the transport) plus the discrete lines wired to the
// CPU's GPIO. inputs() ORs the GPIO e-stop / alarm / limit levels read at
// read_inputs() into the board's snapshot, so an e-stop edge on a GPIO
// line reaches the supervisor at the next tick, like the board's own input;
// a failed GPIO read counts as e-stop asserted (fail safe). The servo
// enables go to the board and, when configured, to the GPIO enable lines
// at write_outputs().
#include <atomic>
#include <cstdint>

#include "drivers/fpga/fpga_io_board.hpp"
#include "drivers/linux/gpio_lines.hpp"
#include "hal/io_board.hpp"

namespace tnv::drivers {

class LinuxIoBoard final : public hal::IoBoard {
 public:
  // `lines` may be null (no GPIO lines configured).
  LinuxIoBoard(FpgaIoBoard& board, BoardLines* lines) noexcept : board_(board), lines_(lines) {}

  hal::HalStatus read_inputs() noexcept override;
  hal::HalStatus write_outputs() noexcept override;
  hal::TickLatch latched_tick() const noexcept override { return board_.latched_tick(); }
  std::uint32_t latched_count(hal::Axis axis) const noexcept override { return board_.latched_count(axis); }
  unsigned counter_bits() const noexcept override { return board_.counter_bits(); }
  hal::IndexLatch index_latch(hal::Axis axis) const noexcept override { return board_.index_latch(axis); }
  void set_code(hal::Axis axis, std::uint16_t code) noexcept override { board_.set_code(axis, code); }
  unsigned dac_bits() const noexcept override { return board_.dac_bits(); }
  hal::DiscreteInputs inputs() const noexcept override;
  void set_servo_enable(hal::Axis axis, bool enabled) noexcept override;
  hal::HalStatus clear_latched_faults() noexcept override { return board_.clear_latched_faults(); }
  std::uint16_t latched_force_code() const noexcept override { return board_.latched_force_code(); }
  unsigned adc_bits() const noexcept override { return board_.adc_bits(); }
  std::uint16_t latched_accel_code(hal::Axis axis) const noexcept override { return board_.latched_accel_code(axis); }
  void kick() noexcept override { board_.kick(); }
  void set_spindle_code(std::uint16_t code) noexcept override { board_.set_spindle_code(code); }
  void set_spindle_enable(bool enabled) noexcept override { board_.set_spindle_enable(enabled); }
  void set_spindle_reverse(bool reverse) noexcept override { board_.set_spindle_reverse(reverse); }
  std::uint32_t spindle_latched_count() const noexcept override { return board_.spindle_latched_count(); }
  hal::IndexLatch spindle_index_latch() const noexcept override { return board_.spindle_index_latch(); }

  // Outputs safe now, outside the tick: DACs mid-scale, enables off (the
  // spindle's too), one write to the board and the GPIO enables. The
  // shutdown path.
  hal::HalStatus force_safe_outputs() noexcept;

  std::uint64_t gpio_read_failures() const noexcept { return gpio_read_failures_.load(std::memory_order_relaxed); }
  std::uint64_t gpio_write_failures() const noexcept { return gpio_write_failures_.load(std::memory_order_relaxed); }

 private:
  FpgaIoBoard& board_;
  BoardLines* lines_;
  InputLevels levels_{};
  bool gpio_failed_ = false;
  std::array<bool, hal::kAxisCount> enables_{};
  std::atomic<std::uint64_t> gpio_read_failures_{0};
  std::atomic<std::uint64_t> gpio_write_failures_{0};
};

}  // namespace tnv::drivers
