#pragma once
// Latched fault: the first reason wins and stays until cleared.
#include <cstddef>
#include <cstdint>
#include <iterator>
#include "hal/listed_enum.hpp"

namespace tnv::fw {

// The reasons, in wire order (append, never renumber): the enum, its names
// and the protocol's value list (can/protocol_messages.hpp) all come from
// this one list.
#define TNV_FAULT_REASONS(X) \
  X(none) \
  X(bus_error)            /* the batched register read or write failed */ \
  X(stale_snapshot)       /* tick sequence or clock did not advance */ \
  X(missed_ticks)         /* more consecutive ticks lost than allowed */ \
  X(estop)                /* e-stop input asserted */ \
  X(servo_alarm)          /* servopack alarm input */ \
  X(limit_switch)         /* hardware limit switch */ \
  X(watchdog_tripped)     /* the board watchdog forced the outputs off */ \
  X(following_error)      /* |x_ref - x| above the speed-scaled limit */ \
  X(position_limit)       /* soft travel limit */ \
  X(speed_limit)          /* measured speed above the limit */ \
  X(non_finite_command)   /* a controller produced NaN/inf */ \
  X(remote_estop)         /* e-stop requested over CAN (TickTask::estop()) */ \
  X(encoder_error)        /* the board's decoder latched an illegal A/B transition */ \
  X(dac_error)            /* the board's DAC readback differs from the code written */ \
  X(late_tick)            /* tick period off nominal by more than the tolerance */ \
  X(encoder_stall)        /* no encoder count for N ticks while driven hard: dead encoder or jammed axis */ \
  X(encoder_implausible)  /* a count step no command or disturbance the axis can meet explains (motion_plausibility.hpp) */ \
  X(runaway)              /* the table accelerates against its command: the drive pushes the wrong way */ \
  X(output_write_failed)  /* an output (DAC, enable, servo-enable line) did not take the value written */ \
  X(homing_failed)        /* a homing cycle ran out of travel: no switch, switch stuck on, or no index (value: travel, limit: bound) */

TNV_LISTED_ENUM(FaultReason, TNV_FAULT_REASONS)

struct FaultRecord {
  FaultReason reason = FaultReason::none;
  std::int8_t axis = -1;     // 0 = x, 1 = y, -1 = not axis-specific
  std::uint64_t tick = 0;    // firmware tick count when latched
  double value = 0.0;        // offending value (mm, mm/s, ticks), 0 if none
  double limit = 0.0;        // the limit it broke
  bool active() const noexcept { return reason != FaultReason::none; }
};

}  // namespace tnv::fw
