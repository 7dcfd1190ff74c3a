#pragma once
// Faults the emulated machine injects on a schedule (scenario `[[fault]]`
// tables, docs/scenarios.md). Each is something that goes wrong on the
// bench, modelled where it happens: in the wiring, the encoder, the DAC,
// the I/O board's tick logic, the drive, or the register bus. The firmware
// is told nothing; it has to notice.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "hal/axis.hpp"
#include "hal/listed_enum.hpp"

namespace tnv::emu {

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

// Every kind once: its name (the scenario file's `kind`) and its keys. The
// enum, kFaultKinds, to_string() and fault_keys() all come from this list.
#define TNV_FAULT_KINDS(X) \
  /* e-stop input asserted */ \
  X(estop, .duration = true) \
  /* servopack alarm input asserted (axis) */ \
  X(servo_alarm, .axis = true, .duration = true) \
  /* hardware limit switch input asserted (axis, side) */ \
  X(limit_switch, .axis = true, .side = true, .duration = true) \
  /* one illegal A/B transition: the decoder latches FAULTS, loses 2 counts (axis) */ \
  X(encoder_illegal, .axis = true) \
  /* A/B lines stop: the count register freezes (axis) */ \
  X(encoder_dead, .axis = true, .duration = true) \
  /* the DAC output sticks at `code` whatever is written (axis) */ \
  X(dac_stuck, .axis = true, .duration = true, .code = true) \
  /* the tick interrupt is lost `ticks` times in a row: the firmware sleeps through them */ \
  X(missed_tick, .ticks = true) \
  /* the board's tick timer stalls: one tick latches `delay_us` late */ \
  X(late_tick, .delay = true) \
  /* the snapshot latch stops updating (sequence and clock frozen), ticks still fire */ \
  X(stale_snapshot, .duration = true) \
  /* the drive's gain sign is flipped (wrong motor phasing): u -> -u (axis) */ \
  X(runaway, .axis = true, .duration = true) \
  /* every register read fails */ \
  X(bus_read_error, .duration = true) \
  /* the count register jumps by `counts` and keeps the offset (noise burst, lost index) (axis) */ \
  X(encoder_jump, .axis = true, .counts = true) \
  /* the next tick's snapshot is an older one again (sequence goes backwards) */ \
  X(snapshot_replayed)

TNV_LISTED_ENUM(FaultKind, TNV_FAULT_KINDS)

inline constexpr std::array kFaultKindKeys{
#define TNV_KEYS(name, ...) FaultKeys{__VA_ARGS__},
    TNV_FAULT_KINDS(TNV_KEYS)
#undef TNV_KEYS
};

inline std::optional<FaultKind> fault_kind_from_string(std::string_view name) noexcept {
  for (FaultKind kind : kFaultKinds)
    if (name == to_string(kind)) return kind;
  return std::nullopt;
}

constexpr FaultKeys fault_keys(FaultKind kind) noexcept {
  const auto i = static_cast<std::size_t>(kind);
  return i < kFaultKindKeys.size() ? kFaultKindKeys[i] : FaultKeys{};
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
