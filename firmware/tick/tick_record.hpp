#pragma once
// What one tick saw and did: the telemetry / trace sample.
#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>

#include "firmware/supervisor/fault.hpp"
#include "hal/axis.hpp"
#include "hal/listed_enum.hpp"

namespace tnv::fw {

// The states, in wire order: the enum, its names and the protocol's value
// list (can/protocol_messages.hpp) all come from this one list.
#define TNV_MOTION_STATES(X) \
  X(disabled)  /* servo off, DACs at mid-scale */ \
  X(dwell)     /* servo on, holding the start point */ \
  X(moving)    /* following the trajectory */ \
  X(holding)   /* servo on, holding the end point */ \
  X(faulted)   /* outputs safe, fault latched */

TNV_LISTED_ENUM(MotionState, TNV_MOTION_STATES)

struct AxisTickRecord {
  double reference_mm = 0.0;
  double reference_speed_mm_s = 0.0;
  double unshaped_reference_mm = 0.0;  // the source's x_ref,k before the input shaper
  double position_mm = 0.0;  // encoder-measured
  double speed_mm_s = 0.0;   // M-method
  double command_mm_s = 0.0; // controller output u_k (with a closed-loop excitation: c_k + d_k)
  double excitation_mm_s = 0.0;  // d_k of an excitation (closed loop: added to the controller's; open loop: u_k), else 0
  std::uint16_t dac_code = 0;
  bool enabled = false;
  double s = 0.0;
  double d_hat_mm_s = 0.0;
  double accel_mm_s2 = 0.0;  // tool-side accelerometer at this tick's latch
};

// The spindle's part of the tick (firmware/spindle/spindle_control.hpp).
struct SpindleTickRecord {
  double measured_rpm = 0.0;  // signed, from the spindle encoder (M-method)
  double command_rpm = 0.0;   // the ramped command (signed), what the DAC is written with while enabled
  double target_rpm = 0.0;    // what was asked for (signed), 0 when commanded off
  std::uint16_t dac_code = 0;
  bool enabled = false;       // the drive's enable output
  bool reverse = false;       // the direction output
  bool at_speed = false;
  bool feed_gate_waiting = false;  // a feed move waited for the spindle this tick
};

struct TickRecord {
  std::uint64_t tick = 0;             // firmware tick count since construction
  std::uint32_t sequence = 0;         // board tick sequence
  std::uint32_t period_clocks = 0;    // measured period (10 MHz clocks)
  MotionState state = MotionState::disabled;
  std::int64_t motion_tick = -1;      // ticks since the start of motion, -1 outside motion
  std::uint16_t force_code = 0;
  std::array<AxisTickRecord, hal::kAxisCount> axis{};
  double feed_override = 1.0;                  // the motion core's feed override this tick
  double arsc_force_ref_n = 0.0;               // the force loop's f* now (soft start included), 0 when off
  double arsc_cutting_gain_n_per_mm_s = 0.0;   // its cutting-gain estimate, 0 when off
  SpindleTickRecord spindle{};
};

struct TickCounters {
  std::uint64_t ticks = 0;
  std::uint64_t missed_ticks = 0;    // board ticks with no firmware tick (sequence gaps)
  std::uint64_t late_ticks = 0;      // measured period beyond the nominal +- tolerance
  std::uint64_t bus_errors = 0;
};

}  // namespace tnv::fw
