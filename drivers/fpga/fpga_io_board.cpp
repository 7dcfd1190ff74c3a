#include "drivers/fpga/fpga_io_board.hpp"

namespace tnv::drivers {

namespace regs = hal::regs;

namespace {
constexpr std::size_t slot(std::uint16_t snapshot_register) noexcept {
  return static_cast<std::size_t>(snapshot_register - regs::kSnapshotFirst);
}
constexpr std::uint32_t dac_mask = (1u << regs::kDacBits) - 1u;
constexpr std::uint32_t encoder_mask = (1u << regs::kEncoderBits) - 1u;

hal::IndexLatch decode_index(std::uint32_t word) noexcept {
  return {word & encoder_mask, static_cast<std::uint8_t>((word >> regs::kIndexEdgesShift) & regs::kIndexEdgesMask)};
}

void set_bit(std::uint32_t& bits, std::uint32_t bit, bool on) noexcept { bits = on ? (bits | bit) : (bits & ~bit); }
}  // namespace

FpgaInitResult FpgaIoBoard::init(const FpgaBoardSettings& settings) noexcept {
  if (settings.tick_divider_clocks == 0) return {hal::HalStatus::bad_address, "tick divider must be > 0"};
  if (settings.watchdog_timeout_clocks <= settings.tick_divider_clocks)
    return {hal::HalStatus::bad_address, "watchdog timeout must be longer than one tick"};

  std::array<std::uint32_t, 2> ident{};
  hal::HalStatus st = bus_.read_block(regs::kId, ident);
  if (st != hal::HalStatus::ok) return {st, "cannot read the I/O board id register"};
  if (ident[0] != regs::kIdValue) return {hal::HalStatus::not_present, "no TNV I/O board at this address (bad id)"};
  const std::uint32_t major = regs::version_major(ident[1]);
  // A major version moves registers: every word this driver reads or writes
  // would be another one on a board of another major.
  if (major < regs::version_major(regs::kVersionValue))
    return {hal::HalStatus::not_present,
            "I/O board 1.x: its register map has room for two axes and puts the output window where 2.0 has the "
            "axis slots; this driver needs a 2.x board (docs/register-map.md)"};
  if (major != regs::version_major(regs::kVersionValue))
    return {hal::HalStatus::not_present, "unsupported I/O board major version: newer than this driver's 2.x map"};
  // An older minor lacks registers this driver reads or writes each tick.
  if (regs::version_minor(ident[1]) < regs::version_minor(regs::kVersionValue))
    return {hal::HalStatus::not_present, "I/O board too old: a lower minor version than this driver's register map (docs/register-map.md)"};

  const std::array<std::uint32_t, 3> config{settings.tick_divider_clocks, settings.watchdog_timeout_clocks,
                                            regs::kControlClearWatchdog | regs::kControlClearFaults};
  st = bus_.write_block(regs::kTickDivider, config);
  if (st != hal::HalStatus::ok) return {st, "cannot program the I/O board configuration registers"};

  dac_codes_.fill(kMidCode);
  spindle_code_ = kMidCode;
  output_bits_ = 0;
  kick_pending_ = false;
  st = write_outputs();
  if (st != hal::HalStatus::ok) return {st, "cannot write safe outputs to the I/O board"};
  return {};
}

hal::HalStatus FpgaIoBoard::read_inputs() noexcept { return bus_.read_block(regs::kSnapshotFirst, snapshot_); }

hal::HalStatus FpgaIoBoard::write_outputs() noexcept {
  std::array<std::uint32_t, regs::kOutputWords> out{};
  for (const hal::Axis a : hal::kAxes) out[regs::axis_registers(a).dac - regs::kOutputFirst] = dac_codes_[hal::index(a)];
  out[regs::kOutputs - regs::kOutputFirst] = output_bits_;
  out[regs::kWatchdogKick - regs::kOutputFirst] = kick_pending_ ? regs::kWatchdogKickKey : 0u;
  out[regs::kDacSpindle - regs::kOutputFirst] = spindle_code_;
  kick_pending_ = false;
  return bus_.write_block(regs::kOutputFirst, out);
}

hal::TickLatch FpgaIoBoard::latched_tick() const noexcept {
  return {snapshot_[slot(regs::kTickClock)], snapshot_[slot(regs::kTickSequence)],
          snapshot_[slot(regs::kClockAtRead)]};
}

std::uint32_t FpgaIoBoard::latched_count(hal::Axis axis) const noexcept {
  return snapshot_[slot(regs::axis_registers(axis).encoder)] & encoder_mask;
}

hal::IndexLatch FpgaIoBoard::index_latch(hal::Axis axis) const noexcept {
  return decode_index(snapshot_[slot(regs::axis_registers(axis).index)]);
}

void FpgaIoBoard::set_code(hal::Axis axis, std::uint16_t code) noexcept {
  dac_codes_[hal::index(axis)] = static_cast<std::uint16_t>(code & dac_mask);
}

hal::DiscreteInputs FpgaIoBoard::inputs() const noexcept {
  const std::uint32_t bits = snapshot_[slot(regs::kInputs)];
  hal::DiscreteInputs in;
  in.estop = (bits & regs::kInputEstop) != 0;
  in.watchdog_tripped = (bits & regs::kInputWatchdogTripped) != 0;
  in.probe = (bits & regs::kInputProbe) != 0;
  const std::uint32_t faults = snapshot_[slot(regs::kFaults)];
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const regs::AxisRegisters& r = regs::kAxisRegisters[i];
    in.servo_alarm[i] = (bits & r.input_alarm) != 0;
    in.limit_positive[i] = (bits & r.input_limit_pos) != 0;
    in.limit_negative[i] = (bits & r.input_limit_neg) != 0;
    in.home_switch[i] = (bits & r.input_home) != 0;
    in.encoder_error[i] = (faults & r.fault_encoder) != 0;
    in.dac_error[i] = (faults & r.fault_dac) != 0;
  }
  return in;
}

void FpgaIoBoard::set_servo_enable(hal::Axis axis, bool enabled) noexcept {
  set_bit(output_bits_, regs::axis_registers(axis).output_enable, enabled);
}

void FpgaIoBoard::set_spindle_code(std::uint16_t code) noexcept {
  spindle_code_ = static_cast<std::uint16_t>(code & dac_mask);
}

void FpgaIoBoard::set_spindle_enable(bool enabled) noexcept {
  set_bit(output_bits_, regs::kOutputSpindleEnable, enabled);
}

void FpgaIoBoard::set_spindle_reverse(bool reverse) noexcept {
  set_bit(output_bits_, regs::kOutputSpindleReverse, reverse);
}

std::uint32_t FpgaIoBoard::spindle_latched_count() const noexcept {
  return snapshot_[slot(regs::kSpindleEncoder)] & encoder_mask;
}

hal::IndexLatch FpgaIoBoard::spindle_index_latch() const noexcept {
  return decode_index(snapshot_[slot(regs::kSpindleIndex)]);
}

std::uint16_t FpgaIoBoard::latched_force_code() const noexcept {
  return static_cast<std::uint16_t>(snapshot_[slot(regs::kAdcForce)] & ((1u << regs::kAdcBits) - 1u));
}

std::uint16_t FpgaIoBoard::latched_accel_code(hal::Axis axis) const noexcept {
  return static_cast<std::uint16_t>(snapshot_[slot(regs::axis_registers(axis).adc_accel)] & ((1u << regs::kAdcBits) - 1u));
}

std::uint32_t FpgaIoBoard::latched_fault_bits() const noexcept { return snapshot_[slot(regs::kFaults)]; }

hal::HalStatus FpgaIoBoard::clear_latched_faults() noexcept {
  const std::array<std::uint32_t, 1> control{regs::kControlClearWatchdog | regs::kControlClearFaults};
  return bus_.write_block(regs::kControl, control);
}

}  // namespace tnv::drivers
