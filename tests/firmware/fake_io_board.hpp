#pragma once
// A scriptable hal::IoBoard for firmware unit tests: the test sets what the
// next snapshot holds and inspects what the tick wrote.
#include <array>
#include <cstdint>

#include "hal/io_board.hpp"

namespace tnv::test {

class FakeIoBoard final : public hal::IoBoard {
 public:
  // --- what the next read_inputs() returns
  hal::TickLatch latch{};
  std::array<std::uint32_t, hal::kAxisCount> counts{};
  hal::DiscreteInputs in{};
  std::array<hal::IndexLatch, hal::kAxisCount> index{};  // the count at the last index edge, and the edge counter
  std::uint16_t force_code = 0;
  hal::HalStatus read_status = hal::HalStatus::ok;
  hal::HalStatus write_status = hal::HalStatus::ok;
  unsigned bits = 16;

  // --- what the tick wrote (staged, then committed by write_outputs)
  std::array<std::uint16_t, hal::kAxisCount> staged_code = hal::per_axis(std::uint16_t{2048});
  std::array<bool, hal::kAxisCount> staged_enable{};
  std::array<std::uint16_t, hal::kAxisCount> written_code = hal::per_axis(std::uint16_t{2048});
  std::array<bool, hal::kAxisCount> written_enable{};
  int reads = 0, writes = 0, kicks = 0;
  bool kick_staged = false;

  // Advances the board by one regular tick.
  void next_tick(std::uint32_t period_clocks = 10'000) {
    latch.clock_10mhz += period_clocks;
    ++latch.sequence;
  }

  hal::HalStatus read_inputs() noexcept override {
    ++reads;
    return read_status;
  }
  hal::HalStatus write_outputs() noexcept override {
    ++writes;
    if (write_status != hal::HalStatus::ok) return write_status;
    written_code = staged_code;
    written_enable = staged_enable;
    if (kick_staged) ++kicks;
    kick_staged = false;
    return hal::HalStatus::ok;
  }
  hal::TickLatch latched_tick() const noexcept override { return latch; }
  std::uint32_t latched_count(hal::Axis a) const noexcept override {
    return counts[hal::index(a)] & ((bits >= 32) ? 0xFFFFFFFFu : ((1u << bits) - 1u));
  }
  unsigned counter_bits() const noexcept override { return bits; }
  hal::IndexLatch index_latch(hal::Axis a) const noexcept override { return index[hal::index(a)]; }
  void set_code(hal::Axis a, std::uint16_t code) noexcept override { staged_code[hal::index(a)] = code; }
  unsigned dac_bits() const noexcept override { return 12; }
  hal::DiscreteInputs inputs() const noexcept override { return in; }
  void set_servo_enable(hal::Axis a, bool e) noexcept override { staged_enable[hal::index(a)] = e; }
  // Like the FPGA: the sticky trips read back clear until raised again.
  hal::HalStatus clear_latched_faults() noexcept override {
    ++latch_clears;
    in.encoder_error = {};
    in.dac_error = {};
    in.watchdog_tripped = false;
    return hal::HalStatus::ok;
  }
  int latch_clears = 0;
  std::uint16_t latched_force_code() const noexcept override { return force_code; }
  unsigned adc_bits() const noexcept override { return 12; }
  std::array<std::uint16_t, hal::kAxisCount> accel_code = hal::per_axis(std::uint16_t{2048});  // offset binary: 2048 = 0 mm/s^2
  std::uint16_t latched_accel_code(hal::Axis a) const noexcept override { return accel_code[hal::index(a)]; }
  void kick() noexcept override { kick_staged = true; }

  // The spindle: what the next snapshot holds, and what the tick staged.
  std::uint32_t spindle_count = 0;
  hal::IndexLatch spindle_index{};
  std::uint16_t spindle_code = 2048;
  bool spindle_enable = false;
  bool spindle_reverse = false;
  void set_spindle_code(std::uint16_t code) noexcept override { spindle_code = code; }
  void set_spindle_enable(bool e) noexcept override { spindle_enable = e; }
  void set_spindle_reverse(bool r) noexcept override { spindle_reverse = r; }
  std::uint32_t spindle_latched_count() const noexcept override { return spindle_count; }
  hal::IndexLatch spindle_index_latch() const noexcept override { return spindle_index; }
};

}  // namespace tnv::test
