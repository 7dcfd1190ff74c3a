#pragma once
// Per-tick safety checks. Pure: given this tick's inputs it returns the
// first fault found (none if all is well); the tick task latches it and
// makes the outputs safe in the same tick.
#include <array>
#include <cmath>
#include <cstdint>

#include "firmware/control/param_check.hpp"
#include "firmware/supervisor/fault.hpp"
#include "firmware/supervisor/motion_plausibility.hpp"
#include "firmware/supervisor/stall_monitor.hpp"
#include "hal/axis.hpp"
#include "hal/discrete_io.hpp"

namespace tnv::fw {

// limit = floor + lag * |commanded speed|: a servo lags its reference by
// roughly speed x (loop time constant), so a fixed limit is either blind
// at rest or trips at speed.
struct FollowingErrorLimit {
  double floor_mm = 0.05;
  double lag_s = 0.02;
  double at(double commanded_speed_mm_s) const noexcept { return floor_mm + lag_s * std::fabs(commanded_speed_mm_s); }
  bool operator==(const FollowingErrorLimit&) const = default;
};

struct AxisLimits {
  double position_min_mm = -250.0;
  double position_max_mm = 250.0;
  double speed_max_mm_s = 150.0;
  FollowingErrorLimit following{};
  StallLimit stall{};
  PlausibilityLimit plausibility{};
  bool operator==(const AxisLimits&) const = default;
};

struct SupervisorConfig {
  std::array<AxisLimits, hal::kAxisCount> axis{};
  std::uint32_t max_consecutive_missed_ticks = 2;
  // Late tick: the measured period, over the ticks it spans, off nominal by
  // more than the tolerance. Half a period: ordinary jitter is absorbed by
  // the M-method's measured period; a tick late or early by half a period or
  // more is a broken real-time loop.
  std::uint32_t tick_period_clocks = 10'000;
  std::uint32_t period_tolerance_clocks = 5'000;
  bool operator==(const SupervisorConfig&) const = default;
};

// The first wrong limit: its member in `config` and why; ok when valid.
ParamCheck check(const SupervisorConfig& config) noexcept;
const char* validate(const SupervisorConfig& config) noexcept;  // "" when valid, else check()'s reason

struct AxisCheckInput {
  double position_mm = 0.0;
  double speed_mm_s = 0.0;
  double reference_mm = 0.0;
  double reference_speed_mm_s = 0.0;
  double command_mm_s = 0.0;
  std::uint32_t stalled_ticks = 0;  // StallMonitor: ticks without a count while driven
  double stall_command_mm_s = 0.0;  // the command that acted over the last of them
  PlausibilityVerdict plausibility{};  // MotionPlausibility: count jump, runaway
  // Off while the axis homes: its frame is not home yet, the homing cycle's
  // own travel bounds stand in for the soft limits.
  bool soft_limits = true;
};

struct SupervisorInput {
  std::uint64_t tick = 0;
  bool bus_ok = true;
  bool snapshot_advanced = true;
  std::uint32_t ticks_missed = 0;  // lost since the previous tick
  std::uint32_t period_clocks = 0;  // measured since the previous tick; 0 = not measured (unchecked)
  hal::DiscreteInputs inputs{};
  bool servo_on = false;  // following error and command checks only apply with the servo on
  std::array<AxisCheckInput, hal::kAxisCount> axis{};
};

FaultRecord check(const SupervisorConfig& config, const SupervisorInput& in) noexcept;

// True while an input-level cause is still asserted (e-stop, watchdog trip,
// servo alarm, limit switch, or a sticky board fault not yet cleared on the
// board): what clear_fault() must refuse on.
bool fault_cause_present(const hal::DiscreteInputs& inputs) noexcept;

}  // namespace tnv::fw
