#pragma once
// Register map of the FPGA I/O board: the single source for the driver
// (drivers/fpga) and the emulated board (emulator/). Documented in
// docs/register-map.md. Word addresses, 32-bit registers.
#include <array>
#include <cstdint>

#include "hal/axis.hpp"

namespace tnv::hal::regs {

// --- identification (read-only)
inline constexpr std::uint16_t kId = 0x000;          // reads kIdValue
inline constexpr std::uint16_t kVersion = 0x001;     // major << 16 | minor
inline constexpr std::uint16_t kClockLive = 0x002;   // free-running 10 MHz counter, now

inline constexpr std::uint32_t kIdValue = 0x544E5634;  // "TNV4"
// A minor version adds registers and bits and moves none: a driver for 1.n
// runs a board 1.m, m >= n. Its history: 1.4 the spindle (SPINDLE_ENCODER,
// SPINDLE_INDEX, DAC_SPINDLE, OUTPUTS bits 8/9), 1.3 home switches and index
// latches, 1.2 tool-side accelerometers, 1.1 DAC readback fault bits.
inline constexpr std::uint32_t kVersionValue = 0x00010004;  // 1.4

// --- snapshot window (read-only, latched at each tick, read in one block)
inline constexpr std::uint16_t kSnapshotFirst = 0x010;
inline constexpr std::uint16_t kTickSequence = 0x010;  // +1 per tick, wraps at 2^32
inline constexpr std::uint16_t kTickClock = 0x011;     // 10 MHz counter at the tick
inline constexpr std::uint16_t kEncoderX = 0x012;      // quadrature count (kEncoderBits wide)
inline constexpr std::uint16_t kEncoderY = 0x013;
inline constexpr std::uint16_t kInputs = 0x014;        // kInput* bits, active = 1
inline constexpr std::uint16_t kAdcForce = 0x015;      // force sensor code (kAdcBits wide)
inline constexpr std::uint16_t kFaults = 0x016;        // kFault* bits, sticky
inline constexpr std::uint16_t kClockAtRead = 0x017;   // 10 MHz counter when this word is read
inline constexpr std::uint16_t kAdcAccelX = 0x018;     // tool-side accelerometer code, x (kAdcBits, offset binary)
inline constexpr std::uint16_t kAdcAccelY = 0x019;     // same for y
inline constexpr std::uint16_t kIndexX = 0x01A;        // count latched at the last index edge | edges << 16 (kIndex* fields)
inline constexpr std::uint16_t kIndexY = 0x01B;        // same for y
inline constexpr std::uint16_t kSpindleEncoder = 0x01C;  // spindle quadrature count (kEncoderBits wide)
inline constexpr std::uint16_t kSpindleIndex = 0x01D;    // as kIndexX, for the spindle's index (once per revolution)
inline constexpr std::uint16_t kSnapshotWords = 14;

// --- output window (read/write, written in one block each tick)
inline constexpr std::uint16_t kOutputFirst = 0x020;
inline constexpr std::uint16_t kDacX = 0x020;          // offset binary, kDacBits wide
inline constexpr std::uint16_t kDacY = 0x021;
inline constexpr std::uint16_t kOutputs = 0x022;       // kOutput* bits
inline constexpr std::uint16_t kWatchdogKick = 0x023;  // write kWatchdogKickKey to reload
inline constexpr std::uint16_t kDacSpindle = 0x024;    // spindle speed command, offset binary, kDacBits wide
inline constexpr std::uint16_t kOutputWords = 5;

// --- configuration (read/write, set at start-up)
inline constexpr std::uint16_t kTickDivider = 0x030;     // clocks per tick (reset: 10,000)
inline constexpr std::uint16_t kWatchdogTimeout = 0x031; // clocks without a kick before trip (reset: 30,000)
inline constexpr std::uint16_t kControl = 0x032;         // write-one-to-act kControl* bits

inline constexpr std::uint16_t kLastRegister = 0x032;

// kInputs bits
inline constexpr std::uint32_t kInputEstop = 1u << 0;
inline constexpr std::uint32_t kInputAlarmX = 1u << 1;
inline constexpr std::uint32_t kInputAlarmY = 1u << 2;
inline constexpr std::uint32_t kInputLimitXPos = 1u << 3;
inline constexpr std::uint32_t kInputLimitXNeg = 1u << 4;
inline constexpr std::uint32_t kInputLimitYPos = 1u << 5;
inline constexpr std::uint32_t kInputLimitYNeg = 1u << 6;
inline constexpr std::uint32_t kInputWatchdogTripped = 1u << 7;
inline constexpr std::uint32_t kInputHomeX = 1u << 8;  // home switch X
inline constexpr std::uint32_t kInputHomeY = 1u << 9;

// kIndexX/Y fields: bits 0..15 the encoder count latched at the most recent
// index edge (kEncoderBits wide, as ENCODER_X/Y); bits 16..23 the number of
// index edges since reset, modulo 256 (a change says a new edge latched).
inline constexpr unsigned kIndexEdgesShift = 16;
inline constexpr std::uint32_t kIndexEdgesMask = 0xFFu;

// kFaults bits (sticky until kControlClearFaults)
inline constexpr std::uint32_t kFaultEncoderX = 1u << 0;  // illegal A/B transition
inline constexpr std::uint32_t kFaultEncoderY = 1u << 1;
inline constexpr std::uint32_t kFaultDacX = 1u << 2;      // DAC output readback differs from DAC_X
inline constexpr std::uint32_t kFaultDacY = 1u << 3;

// kOutputs bits (bits 0..7: the axes' servo enables; 8..: the spindle)
inline constexpr std::uint32_t kOutputEnableX = 1u << 0;
inline constexpr std::uint32_t kOutputEnableY = 1u << 1;
inline constexpr std::uint32_t kOutputSpindleEnable = 1u << 8;   // the spindle drive's enable (run)
inline constexpr std::uint32_t kOutputSpindleReverse = 1u << 9;  // the drive's direction input: 1 = reverse (M4)
inline constexpr std::uint32_t kOutputSpindleBits = kOutputSpindleEnable | kOutputSpindleReverse;

// kControl bits
inline constexpr std::uint32_t kControlClearWatchdog = 1u << 0;
inline constexpr std::uint32_t kControlClearFaults = 1u << 1;

inline constexpr std::uint32_t kWatchdogKickKey = 0x4B49434B;  // "KICK"

// Hardware widths and reset values.
inline constexpr unsigned kEncoderBits = 16;
inline constexpr unsigned kDacBits = 12;
inline constexpr unsigned kAdcBits = 12;
// Tool-side accelerometers (ADC_ACCEL_X/Y): offset binary, 0 = -full scale,
// 2^(kAdcBits-1) = 0, 2^kAdcBits - 1 = +full scale - 1 LSB; +-2 g
// (docs/register-map.md says why), so 1 LSB = 9.5766 mm/s^2.
inline constexpr double kAccelFullScaleMmS2 = 2.0 * 9806.65;
inline constexpr std::uint32_t kDefaultTickDivider = 10'000;
inline constexpr std::uint32_t kDefaultWatchdogTimeout = 30'000;
// The DAC readback comparator latches kFaultDac* at a tick when the output
// (through the readback ADC) and the register are more than this many LSB apart.
inline constexpr std::uint32_t kDacReadbackToleranceCodes = 4;

// One axis' channels on the board: its snapshot and output registers and its
// bits in kInputs, kFaults and kOutputs.
struct AxisRegisters {
  std::uint16_t encoder;
  std::uint16_t adc_accel;
  std::uint16_t index;
  std::uint16_t dac;
  std::uint32_t input_alarm;
  std::uint32_t input_limit_pos;
  std::uint32_t input_limit_neg;
  std::uint32_t input_home;
  std::uint32_t fault_encoder;
  std::uint32_t fault_dac;
  std::uint32_t output_enable;
};

// One row per axis of TNV_AXES, in its order. The addresses are the board's
// wiring (a hardware fact, not derivable from the list): a new axis' row is
// the new board revision's registers. The checks below fail the build when a
// row is missing or two axes share a register or a bit.
inline constexpr std::array<AxisRegisters, kAxisCount> kAxisRegisters{{
    {kEncoderX, kAdcAccelX, kIndexX, kDacX, kInputAlarmX, kInputLimitXPos, kInputLimitXNeg, kInputHomeX,
     kFaultEncoderX, kFaultDacX, kOutputEnableX},
    {kEncoderY, kAdcAccelY, kIndexY, kDacY, kInputAlarmY, kInputLimitYPos, kInputLimitYNeg, kInputHomeY,
     kFaultEncoderY, kFaultDacY, kOutputEnableY},
}};

constexpr const AxisRegisters& axis_registers(Axis axis) noexcept { return kAxisRegisters[index(axis)]; }

// The union of one bit field over every axis (e.g. every servo-enable bit).
constexpr std::uint32_t all_axes(std::uint32_t AxisRegisters::*bit) noexcept {
  std::uint32_t bits = 0;
  for (const AxisRegisters& r : kAxisRegisters) bits |= r.*bit;
  return bits;
}

namespace detail {
constexpr bool in_snapshot(std::uint16_t reg) {
  return reg >= kSnapshotFirst + 2 && reg < kSnapshotFirst + kSnapshotWords && reg != kInputs && reg != kAdcForce &&
         reg != kFaults && reg != kClockAtRead;
}
constexpr bool one_bit(std::uint32_t v) { return v != 0 && (v & (v - 1)) == 0; }
constexpr bool axis_registers_well_formed() {
  std::uint16_t regs_seen[4 * kAxisCount]{};
  std::uint32_t inputs = kInputEstop | kInputWatchdogTripped, faults = 0, outputs = 0;
  std::size_t n = 0;
  for (const AxisRegisters& r : kAxisRegisters) {
    if (!in_snapshot(r.encoder) || !in_snapshot(r.adc_accel) || !in_snapshot(r.index)) return false;
    if (r.dac < kOutputFirst || r.dac >= kOutputFirst + kOutputWords || r.dac == kOutputs || r.dac == kWatchdogKick)
      return false;
    for (const std::uint16_t reg : {r.encoder, r.adc_accel, r.index, r.dac}) {
      for (std::size_t j = 0; j < n; ++j)
        if (regs_seen[j] == reg) return false;
      regs_seen[n++] = reg;
    }
    for (const std::uint32_t b : {r.input_alarm, r.input_limit_pos, r.input_limit_neg, r.input_home}) {
      if (!one_bit(b) || (inputs & b) != 0) return false;
      inputs |= b;
    }
    for (const std::uint32_t b : {r.fault_encoder, r.fault_dac}) {
      if (!one_bit(b) || (faults & b) != 0) return false;
      faults |= b;
    }
    if (!one_bit(r.output_enable) || (outputs & r.output_enable) != 0) return false;
    outputs |= r.output_enable;
  }
  return true;
}
}  // namespace detail
static_assert(detail::axis_registers_well_formed(),
              "kAxisRegisters: one row per axis, each register and bit its own and inside its window");

namespace detail {
constexpr bool spindle_registers_well_formed() {
  for (const AxisRegisters& r : kAxisRegisters)
    for (const std::uint16_t reg : {r.encoder, r.adc_accel, r.index, r.dac})
      if (reg == kSpindleEncoder || reg == kSpindleIndex || reg == kDacSpindle) return false;
  if (!in_snapshot(kSpindleEncoder) || !in_snapshot(kSpindleIndex) || kSpindleEncoder == kSpindleIndex) return false;
  if (kDacSpindle < kOutputFirst || kDacSpindle >= kOutputFirst + kOutputWords || kDacSpindle == kOutputs ||
      kDacSpindle == kWatchdogKick)
    return false;
  return one_bit(kOutputSpindleEnable) && one_bit(kOutputSpindleReverse) &&
         (kOutputSpindleEnable & kOutputSpindleReverse) == 0 &&
         (kOutputSpindleBits & all_axes(&AxisRegisters::output_enable)) == 0;
}
}  // namespace detail
static_assert(detail::spindle_registers_well_formed(),
              "the spindle's registers and bits: their own, inside their windows, apart from every axis'");

}  // namespace tnv::hal::regs
