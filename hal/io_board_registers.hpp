#pragma once
// Register map of the FPGA I/O board: the single source for the driver
// (drivers/fpga) and the emulated board (emulator/). Documented in
// docs/register-map.md. Word addresses, 32-bit registers.
#include <cstdint>

namespace tnv::hal::regs {

// --- identification (read-only)
inline constexpr std::uint16_t kId = 0x000;          // reads kIdValue
inline constexpr std::uint16_t kVersion = 0x001;     // major << 16 | minor
inline constexpr std::uint16_t kClockLive = 0x002;   // free-running 10 MHz counter, now

inline constexpr std::uint32_t kIdValue = 0x544E5634;  // "TNV4"
inline constexpr std::uint32_t kVersionValue = 0x00010003;  // 1.3: home switches, index latches (1.2: tool-side accelerometers, 1.1: DAC readback fault bits)

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
inline constexpr std::uint16_t kSnapshotWords = 12;

// --- output window (read/write, written in one block each tick)
inline constexpr std::uint16_t kOutputFirst = 0x020;
inline constexpr std::uint16_t kDacX = 0x020;          // offset binary, kDacBits wide
inline constexpr std::uint16_t kDacY = 0x021;
inline constexpr std::uint16_t kOutputs = 0x022;       // kOutput* bits
inline constexpr std::uint16_t kWatchdogKick = 0x023;  // write kWatchdogKickKey to reload
inline constexpr std::uint16_t kOutputWords = 4;

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

// kOutputs bits
inline constexpr std::uint32_t kOutputEnableX = 1u << 0;
inline constexpr std::uint32_t kOutputEnableY = 1u << 1;

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

}  // namespace tnv::hal::regs
