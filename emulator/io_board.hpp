#pragma once
// The FPGA I/O board at register level (design notes "The I/O board";
// map in hal/io_board_registers.hpp). Owns the 10 MHz counter, the tick
// latch, the DAC and output registers and the watchdog; the machine feeds
// it encoder and ADC samples at each tick and reads back the speed command.
//
// Decisions the map leaves open:
// - Ticks are latched on sub-step boundaries (every 100 clocks). Nominal tick
//   clocks are multiples of TICK_DIVIDER since reset; a tick latches at the
//   first boundary at or after its nominal clock and TICK_CLOCK holds the
//   counter at that boundary (when the samples were really taken).
//   TICK_DIVIDER writes below 100 (one sub-step) are refused; a new divider
//   counts from the last nominal tick.
// - Before the first tick the snapshot holds the reset state with sequence
//   0xFFFFFFFF, so the first tick reads 0.
// - DAC writes above 2^bits - 1 are refused (false, nothing changed):
//   saturation is the firmware's job. OUTPUTS and CONTROL writes with
//   undefined bits are refused too.
// - Watchdog: armed by the first kick, checked at each sub-step boundary; it
//   trips at the first boundary more than WATCHDOG_TIMEOUT clocks after the
//   last kick. A trip resets the DAC registers (the spindle's too) to
//   mid-scale and clears every OUTPUTS bit; while tripped, DAC/OUTPUTS writes are stored but the outputs
//   stay forced off (u = 0) and kicks are ignored, until CONTROL
//   kControlClearWatchdog (which also disarms until the next kick).
// - INPUTS (with the board's own watchdog-tripped bit), ADC_FORCE, ADC_ACCEL_X/Y and FAULTS
//   are snapshot words like the rest: they change only at ticks.
// - The WATCHDOG_KICK word reads back the last value written; CONTROL reads 0.
// - The spindle: DAC_SPINDLE (the scenario's [spindle] dac_bits wide,
//   refused above) and the OUTPUTS spindle bits go to the spindle drive
//   (spindle_drive.hpp), which the machine steps; SPINDLE_ENCODER and
//   SPINDLE_INDEX are snapshot words the machine samples at the latch.
//   No readback comparator and no fault injection on the spindle's channels.
// - The DAC output is the register's code unless a fault sticks it. At each
//   tick latch a readback comparator checks output against register and
//   latches kFaultDac* when they are more than kDacReadbackToleranceCodes
//   apart (the emulated readback is exact).
// - Deferred outputs ([io] on, output_transport.hpp): writes to the output
//   window (DAC_X/Y, OUTPUTS, WATCHDOG_KICK, DAC_SPINDLE) set the registers at once (a
//   read issued after a write sees it: the transport keeps order) but reach
//   the DACs, the enables and the watchdog only when the machine lands
//   them (land_outputs). Configuration and CONTROL writes act at once.
//   CLOCK_AT_READ then reads the counter plus the tick's read delay.
// Fault injection (emulator/fault_schedule.hpp) acts through stick_dac,
// freeze_snapshot, replay_next_tick, delay_next_tick, raise_faults and set_input.
#include <array>
#include <cstdint>
#include <optional>

#include "emulator/dac_speed_map.hpp"
#include "emulator/scenario.hpp"
#include "emulator/substep_timing.hpp"
#include "hal/axis.hpp"
#include "hal/io_board_registers.hpp"

namespace tnv::emu {

// The output window as one transfer (DAC codes, enable bits, kick).
struct OutputWords {
  std::array<std::uint32_t, hal::kAxisCount> dac_codes{};
  std::uint32_t outputs = 0;
  bool kick = false;  // the watchdog key was written
  std::uint32_t spindle_dac_code = 0;
};

// What the machine hands the board at a tick latch.
struct TickSamples {
  std::array<std::uint32_t, hal::kAxisCount> encoder_registers{};  // already wrapped to kEncoderBits
  std::uint32_t adc_force_code = 0;
  // Tool-side accelerometers (offset binary; mid-scale = 0 mm/s^2).
  std::array<std::uint32_t, hal::kAxisCount> adc_accel_codes = hal::per_axis(1u << (hal::regs::kAdcBits - 1));
  // INDEX_X/Y words (count latched at the last index edge, edge counter).
  std::array<std::uint32_t, hal::kAxisCount> index_registers{};
  // Switches the table actuates (home, and limits when placed in the
  // scenario): kInput* bits ORed into INPUTS with the bench's.
  std::uint32_t position_inputs = 0;
  // SPINDLE_ENCODER (wrapped) and SPINDLE_INDEX (as INDEX_X/Y).
  std::uint32_t spindle_encoder_register = 0;
  std::uint32_t spindle_index_register = 0;
};

class IoBoard {
 public:
  IoBoard(const BoardParams& board, const DacParams& dac, double lead_mm, const NoiseParams& noise = {},
          const SpindleParams& spindle = {}) noexcept;

  // --- bus side; false = unmapped address, or a refused write
  bool read_register(std::uint16_t word, std::uint32_t& value) const noexcept;
  bool write_register(std::uint16_t word, std::uint32_t value) noexcept;
  // Whether write_register() would take this value at this address, with
  // no effect: a block write checks every word before it writes any.
  bool accepts_write(std::uint16_t word, std::uint32_t value) const noexcept;

  // --- machine side
  // Speed command the servopack gets: DAC value, or 0 when the axis is
  // disabled or the watchdog has tripped.
  double command_mm_s(hal::Axis axis) const noexcept { return command_mm_s_[hal::index(axis)]; }
  bool enabled(hal::Axis axis) const noexcept;  // enable bit and watchdog not tripped
  // The spindle drive's inputs: DAC_SPINDLE's output code and the OUTPUTS
  // spindle bits as they reach the drive (the enable gated by the watchdog).
  std::uint32_t spindle_dac_output_code() const noexcept { return drive_spindle_dac_code_; }
  bool spindle_enabled() const noexcept;
  bool spindle_reverse() const noexcept { return (drive_outputs_ & hal::regs::kOutputSpindleReverse) != 0; }

  // Whole sub-steps until the next event (tick latch or watchdog trip), >= 1.
  // Between events the outputs cannot change unless the bus writes.
  std::uint64_t substeps_to_next_event() const noexcept {
    const std::uint64_t to_tick_clocks = next_tick_clocks_ > elapsed_clocks_ ? next_tick_clocks_ - elapsed_clocks_ : 0;
    std::uint64_t substeps = to_tick_clocks == 0 ? 1 : (to_tick_clocks + kSubstepClocks - 1) / kSubstepClocks;
    if (watchdog_armed_ && !watchdog_tripped_) {
      // Trips at the first boundary with elapsed - last kick > timeout.
      const std::uint64_t deadline_clocks = last_kick_clocks_ + watchdog_timeout_clocks_;
      const std::uint64_t to_trip =
          deadline_clocks >= elapsed_clocks_ ? (deadline_clocks - elapsed_clocks_) / kSubstepClocks + 1 : 1;
      if (to_trip < substeps) substeps = to_trip;
    }
    return substeps;
  }
  // Advance the counter by `substeps` (at most substeps_to_next_event());
  // true if a tick latch is due now (call latch_tick before advancing again).
  bool advance_substeps(std::uint64_t substeps) noexcept {
    elapsed_clocks_ += substeps * kSubstepClocks;
    if (watchdog_armed_ && !watchdog_tripped_ && elapsed_clocks_ - last_kick_clocks_ > watchdog_timeout_clocks_) {
      trip_watchdog();
    }
    return elapsed_clocks_ >= next_tick_clocks_;
  }
  bool advance_substep() noexcept { return advance_substeps(1); }
  void latch_tick(const TickSamples& samples) noexcept;
  // Snapshot contents before the first tick (sequence stays 0xFFFFFFFF).
  void preset_snapshot(const TickSamples& samples) noexcept;

  std::uint64_t elapsed_clocks() const noexcept { return elapsed_clocks_; }
  std::uint32_t clock() const noexcept {  // the wrapping 32-bit counter
    return static_cast<std::uint32_t>(clock_start_ + elapsed_clocks_);
  }
  std::uint32_t tick_sequence() const noexcept { return snapshot_[kSeq]; }
  bool watchdog_tripped() const noexcept { return watchdog_tripped_; }
  // Counter (elapsed clocks) at the most recent watchdog trip, if any.
  std::optional<std::uint64_t> last_watchdog_trip_clocks() const noexcept { return last_trip_clocks_; }
  std::uint32_t dac_register(hal::Axis axis) const noexcept { return dac_codes_[hal::index(axis)]; }
  std::uint32_t spindle_dac_register() const noexcept { return spindle_dac_code_; }
  std::uint32_t spindle_dac_mid_code() const noexcept { return spindle_dac_mid_code_; }
  const DacSpeedMap& dac() const noexcept { return dac_; }

  // --- test-bench inputs (kInput* bits except kInputWatchdogTripped)
  void set_input(std::uint32_t bit, bool asserted) noexcept;
  // Sticky fault sources (an encoder's illegal A/B transition).
  void raise_faults(std::uint32_t fault_bits) noexcept { faults_ |= fault_bits; }

  // --- [io] transport (output_transport.hpp)
  void defer_outputs(bool deferred) noexcept { outputs_deferred_ = deferred; }
  // The output window as written since the last take, if anything was written.
  std::optional<OutputWords> take_written_outputs() noexcept;
  // A transfer lands: what the DACs, enables and watchdog act on from now.
  void land_outputs(const OutputWords& words) noexcept;
  // Added to CLOCK_AT_READ: the counter when the read completes.
  void set_read_delay_clocks(std::uint32_t clocks) noexcept { read_delay_clocks_ = clocks; }

  // --- injected faults
  // The DAC output sticks at `code` (<= max code) whatever is written; nullopt releases it.
  void stick_dac(hal::Axis axis, std::optional<std::uint32_t> code) noexcept;
  // What the DAC really outputs (the register's code unless stuck).
  std::uint32_t dac_output_code(hal::Axis axis) const noexcept;
  // While frozen, ticks still fire on schedule but the snapshot window
  // (sequence and clock included) keeps its last contents.
  void freeze_snapshot(bool frozen) noexcept { snapshot_frozen_ = frozen; }
  // The tick timer stalls: the next tick latches `clocks` late (a multiple
  // of kSubstepClocks) and later ticks keep the period from it.
  void delay_next_tick(std::uint64_t clocks) noexcept { next_tick_clocks_ += clocks; }
  // The next tick latch shows the snapshot from two latches ago (its
  // sequence one below the last one read); the latch after it is live again.
  void replay_next_tick() noexcept { replay_next_ = true; }

 private:
  // Snapshot slots, relative to kSnapshotFirst.
  static constexpr std::size_t kSeq = hal::regs::kTickSequence - hal::regs::kSnapshotFirst;
  static constexpr std::size_t kClk = hal::regs::kTickClock - hal::regs::kSnapshotFirst;

  void fill_snapshot(const TickSamples& samples) noexcept;
  void trip_watchdog() noexcept;
  void refresh_commands() noexcept;
  void refresh_command(std::size_t i) noexcept;  // axis slot i only
  std::uint32_t live_inputs() const noexcept;

  DacSpeedMap dac_;
  std::uint64_t clock_start_;
  std::uint64_t elapsed_clocks_ = 0;

  std::uint32_t tick_divider_clocks_ = hal::regs::kDefaultTickDivider;
  std::uint64_t last_nominal_tick_clocks_ = 0;
  std::uint64_t next_tick_clocks_ = hal::regs::kDefaultTickDivider;
  std::array<std::uint32_t, hal::regs::kSnapshotWords> snapshot_{};

  std::array<std::uint32_t, hal::kAxisCount> dac_codes_{};  // registers as written (read back)
  // What the DACs and enables act on: the registers, or with deferred outputs the last landed transfer.
  std::array<std::uint32_t, hal::kAxisCount> drive_dac_codes_{};
  std::uint32_t drive_outputs_ = 0;
  std::uint32_t spindle_dac_mid_code_;
  std::uint32_t spindle_dac_max_code_;
  std::uint32_t spindle_dac_code_;        // DAC_SPINDLE as written
  std::uint32_t drive_spindle_dac_code_;  // what the spindle drive gets (deferred like the axes')
  bool outputs_deferred_ = false;
  bool outputs_written_ = false;  // output window written since take_written_outputs
  bool kick_written_ = false;
  std::uint32_t read_delay_clocks_ = 0;
  std::array<std::optional<std::uint32_t>, hal::kAxisCount> stuck_dac_codes_{};
  bool snapshot_frozen_ = false;
  bool replay_next_ = false;
  std::array<std::uint32_t, hal::regs::kSnapshotWords> previous_snapshot_{};  // the last latch's before it
  std::array<std::uint32_t, hal::regs::kSnapshotWords> older_snapshot_{};     // two latches back
  std::optional<std::array<std::uint32_t, hal::regs::kSnapshotWords>> live_snapshot_;  // hidden by a replay
  std::uint32_t outputs_ = 0;
  std::uint32_t last_kick_word_ = 0;
  std::uint32_t inputs_ = 0;
  std::uint32_t faults_ = 0;

  std::uint32_t watchdog_timeout_clocks_ = hal::regs::kDefaultWatchdogTimeout;
  bool watchdog_armed_ = false;
  bool watchdog_tripped_ = false;
  std::uint64_t last_kick_clocks_ = 0;
  std::optional<std::uint64_t> last_trip_clocks_;

  std::array<double, hal::kAxisCount> command_mm_s_{};
};

}  // namespace tnv::emu
