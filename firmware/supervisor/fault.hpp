#pragma once
// Latched fault: the first reason wins and stays until cleared.
#include <cstdint>

namespace tnv::fw {

enum class FaultReason : std::uint8_t {
  none = 0,
  bus_error,           // the batched register read or write failed
  stale_snapshot,      // tick sequence or clock did not advance
  missed_ticks,        // more consecutive ticks lost than allowed
  estop,               // e-stop input asserted
  servo_alarm,         // servopack alarm input
  limit_switch,        // hardware limit switch
  watchdog_tripped,    // the board watchdog forced the outputs off
  following_error,     // |x_ref - x| above the speed-scaled limit
  position_limit,      // soft travel limit
  speed_limit,         // measured speed above the limit
  non_finite_command,  // a controller produced NaN/inf
  remote_estop,        // e-stop requested over CAN (TickTask::estop())
  encoder_error,       // the board's decoder latched an illegal A/B transition
  dac_error,           // the board's DAC readback differs from the code written
  late_tick,           // tick period off nominal by more than the tolerance
  encoder_stall,       // no encoder count for N ticks while driven hard: dead encoder or jammed axis
  encoder_implausible,  // a count step no command or disturbance the axis can meet explains (motion_plausibility.hpp)
  runaway,              // the table accelerates against its command: the drive pushes the wrong way
  output_write_failed,  // an output (DAC, enable, servo-enable line) did not take the value written
  homing_failed,        // a homing cycle ran out of travel: no switch, switch stuck on, or no index (value: travel, limit: bound)
};

constexpr const char* to_string(FaultReason r) noexcept {
  switch (r) {
    case FaultReason::none: return "none";
    case FaultReason::bus_error: return "bus_error";
    case FaultReason::stale_snapshot: return "stale_snapshot";
    case FaultReason::missed_ticks: return "missed_ticks";
    case FaultReason::estop: return "estop";
    case FaultReason::servo_alarm: return "servo_alarm";
    case FaultReason::limit_switch: return "limit_switch";
    case FaultReason::watchdog_tripped: return "watchdog_tripped";
    case FaultReason::following_error: return "following_error";
    case FaultReason::position_limit: return "position_limit";
    case FaultReason::speed_limit: return "speed_limit";
    case FaultReason::non_finite_command: return "non_finite_command";
    case FaultReason::remote_estop: return "remote_estop";
    case FaultReason::encoder_error: return "encoder_error";
    case FaultReason::dac_error: return "dac_error";
    case FaultReason::late_tick: return "late_tick";
    case FaultReason::encoder_stall: return "encoder_stall";
    case FaultReason::encoder_implausible: return "encoder_implausible";
    case FaultReason::runaway: return "runaway";
    case FaultReason::output_write_failed: return "output_write_failed";
    case FaultReason::homing_failed: return "homing_failed";
  }
  return "unknown";
}

struct FaultRecord {
  FaultReason reason = FaultReason::none;
  std::int8_t axis = -1;     // 0 = x, 1 = y, -1 = not axis-specific
  std::uint64_t tick = 0;    // firmware tick count when latched
  double value = 0.0;        // offending value (mm, mm/s, ticks), 0 if none
  double limit = 0.0;        // the limit it broke
  bool active() const noexcept { return reason != FaultReason::none; }
};

}  // namespace tnv::fw
