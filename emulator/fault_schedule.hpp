#pragma once
// Faults the emulated machine injects on a schedule (scenario `[[fault]]`
// tables, docs/scenarios.md). Each is something that goes wrong on the
// bench, modelled where it happens: in the wiring, the encoder, the DAC,
// the I/O board's tick logic, the drive, or the register bus. The firmware
// is told nothing; it has to notice.
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "hal/axis.hpp"

namespace tnv::emu {

enum class FaultKind : std::uint8_t {
  estop,            // e-stop input asserted
  servo_alarm,      // servopack alarm input asserted (axis)
  limit_switch,     // hardware limit switch input asserted (axis, side)
  encoder_illegal,  // one illegal A/B transition: the decoder latches FAULTS, loses 2 counts (axis)
  encoder_dead,     // A/B lines stop: the count register freezes (axis)
  dac_stuck,        // the DAC output sticks at `code` whatever is written (axis)
  missed_tick,      // the tick interrupt is lost `ticks` times in a row: the firmware sleeps through them
  late_tick,        // the board's tick timer stalls: one tick latches `delay_us` late
  stale_snapshot,   // the snapshot latch stops updating (sequence and clock frozen), ticks still fire
  runaway,          // the drive's gain sign is flipped (wrong motor phasing): u -> -u (axis)
  bus_read_error,   // every register read fails
  encoder_jump,     // the count register jumps by `counts` and keeps the offset (noise burst, lost index) (axis)
  snapshot_replayed,  // the next tick's snapshot is an older one again (sequence goes backwards)
};

inline constexpr std::array kFaultKinds{FaultKind::estop,          FaultKind::servo_alarm,   FaultKind::limit_switch,
                                        FaultKind::encoder_illegal, FaultKind::encoder_dead,  FaultKind::dac_stuck,
                                        FaultKind::missed_tick,     FaultKind::late_tick,     FaultKind::stale_snapshot,
                                        FaultKind::runaway,         FaultKind::bus_read_error, FaultKind::encoder_jump,
                                        FaultKind::snapshot_replayed};

constexpr const char* to_string(FaultKind kind) noexcept {
  switch (kind) {
    case FaultKind::estop: return "estop";
    case FaultKind::servo_alarm: return "servo_alarm";
    case FaultKind::limit_switch: return "limit_switch";
    case FaultKind::encoder_illegal: return "encoder_illegal";
    case FaultKind::encoder_dead: return "encoder_dead";
    case FaultKind::dac_stuck: return "dac_stuck";
    case FaultKind::missed_tick: return "missed_tick";
    case FaultKind::late_tick: return "late_tick";
    case FaultKind::stale_snapshot: return "stale_snapshot";
    case FaultKind::runaway: return "runaway";
    case FaultKind::bus_read_error: return "bus_read_error";
    case FaultKind::encoder_jump: return "encoder_jump";
    case FaultKind::snapshot_replayed: return "snapshot_replayed";
  }
  return "?";
}

inline std::optional<FaultKind> fault_kind_from_string(std::string_view name) noexcept {
  for (FaultKind kind : kFaultKinds)
    if (name == to_string(kind)) return kind;
  return std::nullopt;
}

// Which keys a kind takes besides kind and start_s.
struct FaultKeys {
  bool axis = false;      // required
  bool side = false;      // required (limit_switch)
  bool duration = false;  // optional; 0 / omitted = to the end of the run
  bool code = false;      // required (dac_stuck)
  bool ticks = false;     // optional, default 1 (missed_tick)
  bool delay = false;     // required (late_tick)
  bool counts = false;    // required (encoder_jump)
};

constexpr FaultKeys fault_keys(FaultKind kind) noexcept {
  switch (kind) {
    case FaultKind::estop: return {.duration = true};
    case FaultKind::servo_alarm: return {.axis = true, .duration = true};
    case FaultKind::limit_switch: return {.axis = true, .side = true, .duration = true};
    case FaultKind::encoder_illegal: return {.axis = true};
    case FaultKind::encoder_dead: return {.axis = true, .duration = true};
    case FaultKind::dac_stuck: return {.axis = true, .duration = true, .code = true};
    case FaultKind::missed_tick: return {.ticks = true};
    case FaultKind::late_tick: return {.delay = true};
    case FaultKind::stale_snapshot: return {.duration = true};
    case FaultKind::runaway: return {.axis = true, .duration = true};
    case FaultKind::bus_read_error: return {.duration = true};
    case FaultKind::encoder_jump: return {.axis = true, .counts = true};
    case FaultKind::snapshot_replayed: return {};
  }
  return {};
}

inline constexpr std::uint32_t kMaxMissedTicks = 10'000;
inline constexpr double kMaxLateTickDelayUs = 1e6;
inline constexpr std::int32_t kMaxEncoderJumpCounts = 1'000'000;  // |counts|; the register is 32 bits

struct FaultSpec {
  FaultKind kind = FaultKind::estop;
  double start_s = 0.0;     // machine time; takes effect at the first 10 us sub-step boundary at or after it
  double duration_s = 0.0;  // 0 = to the end of the run (kinds with a duration)
  hal::Axis axis = hal::Axis::x;
  bool positive_side = true;     // limit_switch: the + or the - switch
  std::uint32_t dac_code = 0;    // dac_stuck: 0 .. 2^dac.bits - 1
  std::uint32_t ticks = 1;       // missed_tick: 1 .. kMaxMissedTicks
  double delay_us = 0.0;         // late_tick: > 0, rounded up to whole sub-steps
  std::int32_t counts = 0;       // encoder_jump: nonzero, |counts| <= kMaxEncoderJumpCounts
};

}  // namespace tnv::emu
