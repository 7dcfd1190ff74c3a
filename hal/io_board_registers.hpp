#pragma once
// Register map of the FPGA I/O board: the single source for the driver
// (drivers/fpga) and the emulated board (emulator/). Documented in
// docs/register-map.md. Word addresses, 32-bit registers.
#include <array>
#include <cstddef>
#include <cstdint>

#include "hal/axis.hpp"

namespace tnv::hal::regs {

// --- identification (read-only)
inline constexpr std::uint16_t kId = 0x000;          // reads kIdValue
inline constexpr std::uint16_t kVersion = 0x001;     // major << 16 | minor
inline constexpr std::uint16_t kClockLive = 0x002;   // free-running 10 MHz counter, now

inline constexpr std::uint32_t kIdValue = 0x544E5634;  // "TNV4"
// A minor version adds registers and bits and moves none: a driver for 2.n
// runs a board 2.m, m >= n. A major version moves them: 2.0 made room for
// four axes (the 1.x map, up to 1.4, had room for two and the spindle).
inline constexpr std::uint32_t kVersionValue = 0x00020000;  // 2.0
constexpr std::uint32_t version_major(std::uint32_t version) noexcept { return version >> 16; }
constexpr std::uint32_t version_minor(std::uint32_t version) noexcept { return version & 0xFFFFu; }

// Axis slots: the board has channels for kMaxAxes axes; axis i of the list
// (TNV_AXES) is wired to slot i, so its registers and bits follow from its
// index (axis_slot below). A fourth axis is a line in the list.
inline constexpr std::size_t kMaxAxes = 4;

// --- snapshot window (read-only, latched at each tick, read in one block):
// the board's words, then three words per axis slot.
inline constexpr std::uint16_t kSnapshotFirst = 0x010;
inline constexpr std::uint16_t kTickSequence = 0x010;  // +1 per tick, wraps at 2^32
inline constexpr std::uint16_t kTickClock = 0x011;     // 10 MHz counter at the tick
inline constexpr std::uint16_t kInputs = 0x012;        // kInput* bits, active = 1
inline constexpr std::uint16_t kFaults = 0x013;        // kFault* bits, sticky
inline constexpr std::uint16_t kAdcForce = 0x014;      // force sensor code (kAdcBits wide)
inline constexpr std::uint16_t kClockAtRead = 0x015;   // 10 MHz counter when this word is read
inline constexpr std::uint16_t kSpindleEncoder = 0x016;  // spindle quadrature count (kEncoderBits wide)
inline constexpr std::uint16_t kSpindleIndex = 0x017;    // as an axis' index word, for the spindle (once per revolution)
inline constexpr std::uint16_t kAxisSnapshotFirst = 0x018;  // slot i: encoder, accelerometer, index at + 3 i
inline constexpr std::uint16_t kAxisSnapshotStride = 3;
inline constexpr std::uint16_t kSnapshotWindowEnd = static_cast<std::uint16_t>(kAxisSnapshotFirst + kAxisSnapshotStride * kMaxAxes);  // 0x024, past the last slot
// The words read per tick: the board's and the slots of the list's axes
// (14 for two axes, 17 for three, 20 for four).
inline constexpr std::uint16_t kSnapshotWords =
    static_cast<std::uint16_t>(kAxisSnapshotFirst - kSnapshotFirst + kAxisSnapshotStride * kAxisCount);

// --- output window (read/write, written in one block each tick): the
// board's words, then one DAC per axis slot.
inline constexpr std::uint16_t kOutputFirst = 0x028;
inline constexpr std::uint16_t kOutputs = 0x028;       // kOutput* bits
inline constexpr std::uint16_t kWatchdogKick = 0x029;  // write kWatchdogKickKey to reload
inline constexpr std::uint16_t kDacSpindle = 0x02A;    // spindle speed command, offset binary, kDacBits wide
inline constexpr std::uint16_t kAxisDacFirst = 0x02B;  // slot i's DAC at + i, offset binary, kDacBits wide
inline constexpr std::uint16_t kOutputWindowEnd = static_cast<std::uint16_t>(kAxisDacFirst + kMaxAxes);  // 0x02F, past the last slot
// The words written per tick (5 for two axes).
inline constexpr std::uint16_t kOutputWords = static_cast<std::uint16_t>(kAxisDacFirst - kOutputFirst + kAxisCount);

// --- configuration (read/write, set at start-up)
inline constexpr std::uint16_t kTickDivider = 0x030;     // clocks per tick (reset: 10,000)
inline constexpr std::uint16_t kWatchdogTimeout = 0x031; // clocks without a kick before trip (reset: 30,000)
inline constexpr std::uint16_t kControl = 0x032;         // write-one-to-act kControl* bits

inline constexpr std::uint16_t kLastRegister = 0x032;

// kInputs bits: the board's in bits 0..3, then four per axis slot from bit 4.
inline constexpr std::uint32_t kInputEstop = 1u << 0;
inline constexpr std::uint32_t kInputWatchdogTripped = 1u << 1;
inline constexpr std::uint32_t kInputProbe = 1u << 2;  // touch probe: 1 = deflected (docs/machine.md)
inline constexpr unsigned kInputAxisFirstBit = 4;       // slot i: alarm, limit +, limit -, home at 4 + 4 i
inline constexpr unsigned kInputAxisStride = 4;

// kIndex fields (an axis' index word, SPINDLE_INDEX): bits 0..15 the encoder
// count latched at the most recent index edge (kEncoderBits wide, as the
// encoder word); bits 16..23 the number of index edges since reset, modulo
// 256 (a change says a new edge latched).
inline constexpr unsigned kIndexEdgesShift = 16;
inline constexpr std::uint32_t kIndexEdgesMask = 0xFFu;

// kFaults bits (sticky until kControlClearFaults): slot i's encoder (illegal
// A/B transition) at bit i, its DAC readback at bit 4 + i.
inline constexpr unsigned kFaultDacFirstBit = 4;

// kOutputs bits (bits 0..7: the axes' servo enables, slot i at bit i; 8..: the spindle)
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

// Slot i's registers and bits (i < kMaxAxes).
constexpr AxisRegisters axis_slot(std::size_t i) noexcept {
  const auto at = [i](std::uint16_t first, std::size_t stride, std::size_t offset) {
    return static_cast<std::uint16_t>(first + stride * i + offset);
  };
  const unsigned in = kInputAxisFirstBit + kInputAxisStride * static_cast<unsigned>(i);
  return {at(kAxisSnapshotFirst, kAxisSnapshotStride, 0),
          at(kAxisSnapshotFirst, kAxisSnapshotStride, 1),
          at(kAxisSnapshotFirst, kAxisSnapshotStride, 2),
          at(kAxisDacFirst, 1, 0),
          1u << in,
          1u << (in + 1),
          1u << (in + 2),
          1u << (in + 3),
          1u << i,
          1u << (kFaultDacFirstBit + i),
          1u << i};
}

static_assert(kAxisCount <= kMaxAxes, "the 2.x board has channels for four axes: a fifth needs a new map");
static_assert(kSnapshotWindowEnd <= kOutputFirst && kOutputWindowEnd <= kTickDivider,
              "every slot's words inside its window, the windows apart");
static_assert(kInputAxisFirstBit + kInputAxisStride * kMaxAxes <= 32 &&
                  ((kInputEstop | kInputWatchdogTripped | kInputProbe) >> kInputAxisFirstBit) == 0 &&
                  kFaultDacFirstBit >= kMaxAxes && kFaultDacFirstBit + kMaxAxes <= 32 &&
                  (kOutputSpindleBits & ((1u << kMaxAxes) - 1u)) == 0,
              "every slot's bits apart from the board's and the other slots'");

// One row per axis of TNV_AXES, in its order: axis i on slot i. The checks
// below fail the build when two axes share a register or a bit or a row
// leaves its window.
inline constexpr std::array<AxisRegisters, kAxisCount> kAxisRegisters = [] {
  std::array<AxisRegisters, kAxisCount> rows{};
  for (std::size_t i = 0; i < kAxisCount; ++i) rows[i] = axis_slot(i);
  return rows;
}();

// The first two slots by name, for the benches and tests that drive X and Y
// by address.
inline constexpr std::uint16_t kEncoderX = axis_slot(0).encoder;
inline constexpr std::uint16_t kEncoderY = axis_slot(1).encoder;
inline constexpr std::uint16_t kAdcAccelX = axis_slot(0).adc_accel;
inline constexpr std::uint16_t kAdcAccelY = axis_slot(1).adc_accel;
inline constexpr std::uint16_t kIndexX = axis_slot(0).index;
inline constexpr std::uint16_t kIndexY = axis_slot(1).index;
inline constexpr std::uint16_t kDacX = axis_slot(0).dac;
inline constexpr std::uint16_t kDacY = axis_slot(1).dac;
inline constexpr std::uint32_t kInputAlarmX = axis_slot(0).input_alarm;
inline constexpr std::uint32_t kInputAlarmY = axis_slot(1).input_alarm;
inline constexpr std::uint32_t kInputLimitXPos = axis_slot(0).input_limit_pos;
inline constexpr std::uint32_t kInputLimitXNeg = axis_slot(0).input_limit_neg;
inline constexpr std::uint32_t kInputLimitYPos = axis_slot(1).input_limit_pos;
inline constexpr std::uint32_t kInputLimitYNeg = axis_slot(1).input_limit_neg;
inline constexpr std::uint32_t kInputHomeX = axis_slot(0).input_home;
inline constexpr std::uint32_t kInputHomeY = axis_slot(1).input_home;
inline constexpr std::uint32_t kFaultEncoderX = axis_slot(0).fault_encoder;
inline constexpr std::uint32_t kFaultEncoderY = axis_slot(1).fault_encoder;
inline constexpr std::uint32_t kFaultDacX = axis_slot(0).fault_dac;
inline constexpr std::uint32_t kFaultDacY = axis_slot(1).fault_dac;
inline constexpr std::uint32_t kOutputEnableX = axis_slot(0).output_enable;
inline constexpr std::uint32_t kOutputEnableY = axis_slot(1).output_enable;

constexpr const AxisRegisters& axis_registers(Axis axis) noexcept { return kAxisRegisters[index(axis)]; }

// The union of one bit field over every axis (e.g. every servo-enable bit).
constexpr std::uint32_t all_axes(std::uint32_t AxisRegisters::*bit) noexcept {
  std::uint32_t bits = 0;
  for (const AxisRegisters& r : kAxisRegisters) bits |= r.*bit;
  return bits;
}

namespace detail {
// In the snapshot window (up to `end`), not one of the board's own words.
constexpr bool in_snapshot(std::uint16_t reg, std::uint16_t end = kSnapshotFirst + kSnapshotWords) {
  return reg >= kSnapshotFirst + 2 && reg < end && reg != kInputs && reg != kAdcForce && reg != kFaults &&
         reg != kClockAtRead && reg != kSpindleEncoder && reg != kSpindleIndex;
}
constexpr bool in_outputs(std::uint16_t reg, std::uint16_t end = kOutputFirst + kOutputWords) {
  return reg >= kOutputFirst && reg < end && reg != kOutputs && reg != kWatchdogKick && reg != kDacSpindle;
}
constexpr bool one_bit(std::uint32_t v) { return v != 0 && (v & (v - 1)) == 0; }
// Rows 0..n-1 of `row`: each register and bit its own, inside its window.
template <class Row>
constexpr bool rows_well_formed(std::size_t n_rows, Row row, std::uint16_t snapshot_end, std::uint16_t output_end) {
  std::uint16_t regs_seen[4 * kMaxAxes]{};
  std::uint32_t inputs = kInputEstop | kInputWatchdogTripped | kInputProbe, faults = 0, outputs = kOutputSpindleBits;
  std::size_t n = 0;
  for (std::size_t i = 0; i < n_rows; ++i) {
    const AxisRegisters r = row(i);
    if (!in_snapshot(r.encoder, snapshot_end) || !in_snapshot(r.adc_accel, snapshot_end) ||
        !in_snapshot(r.index, snapshot_end))
      return false;
    if (!in_outputs(r.dac, output_end)) return false;
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
constexpr bool axis_registers_well_formed() {
  return rows_well_formed(kAxisCount, [](std::size_t i) { return kAxisRegisters[i]; },
                          kSnapshotFirst + kSnapshotWords, kOutputFirst + kOutputWords);
}
constexpr bool every_slot_well_formed() {
  return rows_well_formed(kMaxAxes, [](std::size_t i) { return axis_slot(i); }, kSnapshotWindowEnd, kOutputWindowEnd);
}
}  // namespace detail
static_assert(detail::every_slot_well_formed(),
              "the four axis slots: each register and bit its own and inside its window");
static_assert(detail::axis_registers_well_formed(),
              "kAxisRegisters: one row per axis, each register and bit its own and inside its window");

namespace detail {
constexpr bool spindle_registers_well_formed() {
  for (const AxisRegisters& r : kAxisRegisters)
    for (const std::uint16_t reg : {r.encoder, r.adc_accel, r.index, r.dac})
      if (reg == kSpindleEncoder || reg == kSpindleIndex || reg == kDacSpindle) return false;
  // Among the board's own words, before the axis slots.
  for (const std::uint16_t reg : {kSpindleEncoder, kSpindleIndex})
    if (reg < kSnapshotFirst + 2 || reg >= kAxisSnapshotFirst || reg == kInputs || reg == kAdcForce ||
        reg == kFaults || reg == kClockAtRead)
      return false;
  if (kSpindleEncoder == kSpindleIndex) return false;
  if (kDacSpindle < kOutputFirst || kDacSpindle >= kAxisDacFirst || kDacSpindle == kOutputs ||
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
