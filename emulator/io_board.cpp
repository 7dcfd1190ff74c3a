#include "emulator/io_board.hpp"

#include <array>
#include <cstdint>
#include <optional>

namespace tnv::emu {

namespace regs = hal::regs;

namespace {
constexpr std::uint32_t kEnableBits = regs::all_axes(&regs::AxisRegisters::output_enable);
constexpr std::uint32_t kOutputBits = kEnableBits | regs::kOutputSpindleBits;  // every defined OUTPUTS bit
constexpr std::uint32_t kControlBits = regs::kControlClearWatchdog | regs::kControlClearFaults;
constexpr std::uint32_t kBenchInputBits = regs::kInputEstop | regs::kInputProbe |
                                          regs::all_axes(&regs::AxisRegisters::input_alarm) |
                                          regs::all_axes(&regs::AxisRegisters::input_limit_pos) |
                                          regs::all_axes(&regs::AxisRegisters::input_limit_neg);
constexpr std::uint32_t kMinTickDividerClocks = kSubstepClocks;

constexpr std::uint32_t enable_bit(hal::Axis axis) { return regs::axis_registers(axis).output_enable; }

// word -> the axis slot whose `member` register it is, -1 for another word:
// built once from the register map, so a register access is one load, not
// a search over the axes (it runs for every word of every tick).
using WordAxisTable = std::array<std::int8_t, regs::kLastRegister + 1>;
constexpr WordAxisTable word_axis_table(std::uint16_t regs::AxisRegisters::*member) {
  WordAxisTable table{};
  table.fill(-1);
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) table[regs::kAxisRegisters[i].*member] = static_cast<std::int8_t>(i);
  return table;
}
constexpr WordAxisTable kDacAxis = word_axis_table(&regs::AxisRegisters::dac);

constexpr std::array<bool, regs::kLastRegister + 1> axis_snapshot_words() {
  std::array<bool, regs::kLastRegister + 1> words{};
  for (const auto member :
       {&regs::AxisRegisters::encoder, &regs::AxisRegisters::adc_accel, &regs::AxisRegisters::index}) {
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) words[regs::kAxisRegisters[i].*member] = true;
  }
  words[regs::kSpindleEncoder] = true;
  words[regs::kSpindleIndex] = true;
  return words;
}
constexpr std::array<bool, regs::kLastRegister + 1> kAxisSnapshotWord = axis_snapshot_words();

// The axis whose DAC register `word` is, none for another word.
constexpr std::optional<std::size_t> dac_axis_of(std::uint16_t word) {
  if (word > regs::kLastRegister || kDacAxis[word] < 0) return std::nullopt;
  return static_cast<std::size_t>(kDacAxis[word]);
}

constexpr bool axis_snapshot_word(std::uint16_t word) { return word <= regs::kLastRegister && kAxisSnapshotWord[word]; }
}  // namespace

IoBoard::IoBoard(const BoardParams& board, const DacParams& dac, double lead_mm, const NoiseParams& noise,
                 const SpindleParams& spindle) noexcept
    : dac_(dac, lead_mm, noise.dac_offset_v, noise.dac_gain_error),
      clock_start_(board.clock_start),
      spindle_dac_mid_code_(std::uint32_t{1} << (spindle.dac_bits - 1)),
      spindle_dac_max_code_((std::uint32_t{1} << spindle.dac_bits) - 1),
      spindle_dac_code_(spindle_dac_mid_code_),
      drive_spindle_dac_code_(spindle_dac_mid_code_) {
  dac_codes_.fill(dac_.mid_code());
  drive_dac_codes_ = dac_codes_;
  snapshot_[kSeq] = 0xFFFF'FFFFu;  // the first tick reads 0
  snapshot_[kClk] = clock();
  refresh_commands();
}

bool IoBoard::enabled(hal::Axis axis) const noexcept {
  return !watchdog_tripped_ && (drive_outputs_ & enable_bit(axis)) != 0;
}

bool IoBoard::spindle_enabled() const noexcept {
  return !watchdog_tripped_ && (drive_outputs_ & regs::kOutputSpindleEnable) != 0;
}

bool IoBoard::read_register(std::uint16_t word, std::uint32_t& value) const noexcept {
  if (axis_snapshot_word(word)) {
    value = snapshot_[word - regs::kSnapshotFirst];
    return true;
  }
  if (const std::optional<std::size_t> i = dac_axis_of(word)) {
    value = dac_codes_[*i];
    return true;
  }
  switch (word) {
    case regs::kId: value = regs::kIdValue; return true;
    case regs::kVersion: value = regs::kVersionValue; return true;
    case regs::kClockLive: value = clock(); return true;
    case regs::kClockAtRead: value = clock() + read_delay_clocks_; return true;
    case regs::kTickSequence:
    case regs::kTickClock:
    case regs::kInputs:
    case regs::kAdcForce:
    case regs::kFaults: value = snapshot_[word - regs::kSnapshotFirst]; return true;
    case regs::kOutputs: value = outputs_; return true;
    case regs::kWatchdogKick: value = last_kick_word_; return true;
    case regs::kDacSpindle: value = spindle_dac_code_; return true;
    case regs::kTickDivider: value = tick_divider_clocks_; return true;
    case regs::kWatchdogTimeout: value = watchdog_timeout_clocks_; return true;
    case regs::kControl: value = 0; return true;  // write-one-to-act
    default: return false;
  }
}

bool IoBoard::accepts_write(std::uint16_t word, std::uint32_t value) const noexcept {
  if (dac_axis_of(word)) return value <= dac_.max_code();
  switch (word) {
    case regs::kDacSpindle:
      return value <= spindle_dac_max_code_;
    case regs::kOutputs:
      return (value & ~kOutputBits) == 0;
    case regs::kWatchdogKick:
    case regs::kWatchdogTimeout:
      return true;
    case regs::kTickDivider:
      return value >= kMinTickDividerClocks;
    case regs::kControl:
      return (value & ~kControlBits) == 0;
    default:
      return false;  // read-only or unmapped
  }
}

bool IoBoard::write_register(std::uint16_t word, std::uint32_t value) noexcept {
  if (!accepts_write(word, value)) return false;
  if (const std::optional<std::size_t> i = dac_axis_of(word)) {
    dac_codes_[*i] = value;
    if (outputs_deferred_) {
      outputs_written_ = true;
      return true;
    }
    drive_dac_codes_[*i] = value;
    refresh_command(*i);  // the other axes' commands do not depend on this word
    return true;
  }
  switch (word) {
    case regs::kDacSpindle:
      spindle_dac_code_ = value;
      if (outputs_deferred_) {
        outputs_written_ = true;
      } else {
        drive_spindle_dac_code_ = value;
      }
      return true;
    case regs::kOutputs:
      outputs_ = value;
      if (outputs_deferred_) {
        outputs_written_ = true;
        return true;
      }
      drive_outputs_ = value;
      refresh_commands();
      return true;
    case regs::kWatchdogKick:
      last_kick_word_ = value;
      if (outputs_deferred_) {
        outputs_written_ = true;
        kick_written_ = kick_written_ || value == regs::kWatchdogKickKey;
        return true;
      }
      if (value == regs::kWatchdogKickKey && !watchdog_tripped_) {
        watchdog_armed_ = true;
        last_kick_clocks_ = elapsed_clocks_;
      }
      return true;
    case regs::kTickDivider:
      tick_divider_clocks_ = value;
      next_tick_clocks_ = last_nominal_tick_clocks_ + value;
      return true;
    case regs::kWatchdogTimeout:
      watchdog_timeout_clocks_ = value;
      return true;
    case regs::kControl:
      if ((value & regs::kControlClearWatchdog) != 0) {
        watchdog_tripped_ = false;
        watchdog_armed_ = false;
        refresh_commands();
      }
      if ((value & regs::kControlClearFaults) != 0) faults_ = 0;
      return true;
    default:
      return false;  // unreachable: accepts_write() refused it
  }
}

void IoBoard::latch_tick(const TickSamples& samples) noexcept {
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const std::uint32_t output = dac_output_code(hal::axis_from_index(i));
    // Against the code the DAC was given (the register's, or the last landed one when outputs are deferred).
    const std::uint32_t given = drive_dac_codes_[i];
    const std::uint32_t apart = output > given ? output - given : given - output;
    if (apart > regs::kDacReadbackToleranceCodes) faults_ |= regs::kAxisRegisters[i].fault_dac;
  }
  if (!snapshot_frozen_) {
    if (live_snapshot_) {
      snapshot_ = *live_snapshot_;  // the replay showed for one latch only
      live_snapshot_.reset();
    }
    older_snapshot_ = previous_snapshot_;
    previous_snapshot_ = snapshot_;
    ++snapshot_[kSeq];
    fill_snapshot(samples);
    if (replay_next_) {
      replay_next_ = false;
      live_snapshot_ = snapshot_;
      snapshot_ = older_snapshot_;
    }
  }
  // Latest nominal tick at or before now; a divider >= one sub-step means
  // at most one is due per boundary except right after a divider write.
  const std::uint64_t late_clocks = elapsed_clocks_ - next_tick_clocks_;
  last_nominal_tick_clocks_ = next_tick_clocks_ + late_clocks / tick_divider_clocks_ * tick_divider_clocks_;
  next_tick_clocks_ = last_nominal_tick_clocks_ + tick_divider_clocks_;
}

void IoBoard::preset_snapshot(const TickSamples& samples) noexcept { fill_snapshot(samples); }

void IoBoard::fill_snapshot(const TickSamples& samples) noexcept {
  snapshot_[kClk] = clock();
  snapshot_[regs::kInputs - regs::kSnapshotFirst] = live_inputs() | samples.position_inputs;
  snapshot_[regs::kAdcForce - regs::kSnapshotFirst] = samples.adc_force_code;
  snapshot_[regs::kFaults - regs::kSnapshotFirst] = faults_;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const regs::AxisRegisters& r = regs::kAxisRegisters[i];
    snapshot_[r.encoder - regs::kSnapshotFirst] = samples.encoder_registers[i];
    snapshot_[r.adc_accel - regs::kSnapshotFirst] = samples.adc_accel_codes[i];
    snapshot_[r.index - regs::kSnapshotFirst] = samples.index_registers[i];
  }
  snapshot_[regs::kSpindleEncoder - regs::kSnapshotFirst] = samples.spindle_encoder_register;
  snapshot_[regs::kSpindleIndex - regs::kSnapshotFirst] = samples.spindle_index_register;
}

void IoBoard::set_input(std::uint32_t bit, bool asserted) noexcept {
  bit &= kBenchInputBits;  // the watchdog bit belongs to the board
  inputs_ = asserted ? (inputs_ | bit) : (inputs_ & ~bit);
}

std::uint32_t IoBoard::live_inputs() const noexcept {
  return inputs_ | (watchdog_tripped_ ? regs::kInputWatchdogTripped : 0u);
}

void IoBoard::trip_watchdog() noexcept {
  watchdog_tripped_ = true;
  last_trip_clocks_ = elapsed_clocks_;
  dac_codes_.fill(dac_.mid_code());
  spindle_dac_code_ = spindle_dac_mid_code_;
  outputs_ &= ~kOutputBits;
  drive_dac_codes_ = dac_codes_;
  drive_spindle_dac_code_ = spindle_dac_code_;
  drive_outputs_ &= ~kOutputBits;
  refresh_commands();
}

std::optional<OutputWords> IoBoard::take_written_outputs() noexcept {
  if (!outputs_written_) return std::nullopt;
  const OutputWords words{dac_codes_, outputs_, kick_written_, spindle_dac_code_};
  outputs_written_ = false;
  kick_written_ = false;
  return words;
}

void IoBoard::land_outputs(const OutputWords& words) noexcept {
  // The write reaches the board now: the registers take it too (a trip in
  // between had reset them; a later write still in flight lands after this).
  dac_codes_ = words.dac_codes;
  outputs_ = words.outputs;
  spindle_dac_code_ = words.spindle_dac_code;
  drive_dac_codes_ = words.dac_codes;
  drive_outputs_ = words.outputs;
  drive_spindle_dac_code_ = words.spindle_dac_code;
  if (words.kick && !watchdog_tripped_) {
    watchdog_armed_ = true;
    last_kick_clocks_ = elapsed_clocks_;
  }
  refresh_commands();
}

void IoBoard::stick_dac(hal::Axis axis, std::optional<std::uint32_t> code) noexcept {
  if (code && *code > dac_.max_code()) code = dac_.max_code();
  stuck_dac_codes_[hal::index(axis)] = code;
  refresh_commands();
}

std::uint32_t IoBoard::dac_output_code(hal::Axis axis) const noexcept {
  const std::size_t i = hal::index(axis);
  return stuck_dac_codes_[i] ? *stuck_dac_codes_[i] : drive_dac_codes_[i];
}

void IoBoard::refresh_command(std::size_t i) noexcept {
  const hal::Axis axis = hal::axis_from_index(i);
  command_mm_s_[i] = enabled(axis) ? dac_.speed_mm_s(dac_output_code(axis)) : 0.0;
}

void IoBoard::refresh_commands() noexcept {
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) refresh_command(i);
}

}  // namespace tnv::emu
