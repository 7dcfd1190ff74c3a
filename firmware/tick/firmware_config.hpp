#pragma once
// Everything the tick task is built from. Validated as a whole before it
// reaches the tick: a bad set is rejected entire, never half-applied.
#include <array>

#include "firmware/adaptive/arsc/arsc_source_params.hpp"
#include "firmware/compensation/friction_feedforward.hpp"
#include "firmware/compensation/screw_compensation.hpp"
#include "firmware/control/axis_controller.hpp"
#include "firmware/control/axis_model.hpp"
#include "firmware/control/param_check.hpp"
#include "firmware/control/pid_params.hpp"
#include "firmware/control/sliding_mode_params.hpp"
#include "firmware/control/speed_observer.hpp"
#include "firmware/homing/homing_cycle.hpp"
#include "firmware/io/dac_code.hpp"
#include "firmware/motion/motion_limits.hpp"
#include "firmware/supervisor/supervisor.hpp"
#include "firmware/trajectory/jog_limits.hpp"
#include "firmware/spindle/spindle_params.hpp"
#include "hal/axis.hpp"

namespace tnv::fw {

// One axis' limits for the look-ahead planner (firmware/motion/); its soft
// limits are the supervisor's position limits.
struct PathLimits {
  double speed_mm_s = 100.0;
  double accel_mm_s2 = 500.0;
  double jerk_mm_s3 = 50000.0;
  bool operator==(const PathLimits&) const = default;
};

struct AxisConfig {
  double count_mm = 10.0 / 24000.0;  // encoder: lead / counts per rev (x4)
  DacScale dac{};
  double home_position_mm = 0.0;     // position assigned to the first encoder reading
  AxisModel model{};                 // the discrete model the controllers believe
  SlidingModeParams sliding{};       // R-DVSC+DDC; DVSC+DDC uses the same with gamma = 0
                                     // (S1 Tables 1/2 are identical except gamma)
  PidParams pid{};
  ControllerKind controller = ControllerKind::rdvsc;
  JogLimits jog{};                   // operator jog: speed, acceleration, dead-man timeout
  PathLimits path{};                 // the look-ahead planner's speed, acceleration and jerk (docs/motion.md)
  FrictionFeedForward friction{};    // friction feed-forward (issue 7); off by default
  SpeedObserverParams observer{};    // speed observer fed back instead of the M-method (issue 7); off by default
  HomingParams homing{};             // the homing cycle: switch side, speeds, home position, travel bounds
  ScrewCompensation screw{};         // backlash and lead-error compensation (issue 16); off by default
  bool operator==(const AxisConfig&) const = default;
};

// The force sensor on the I/O board's ADC (force_code.hpp): its scale is a
// fact of the sensor, like the DAC scale.
struct ForceSensorConfig {
  double n_per_volt = 30.0;  // force per ADC volt (S3 experiment: 1/30 V per N)
  bool operator==(const ForceSensorConfig&) const = default;
};

struct FirmwareConfig {
  std::array<AxisConfig, hal::kAxisCount> axis{};
  SupervisorConfig supervisor{};
  double path_tolerance_mm = 0.005;  // corner blends and arc lag of planned paths stay within this
  ForceSensorConfig force_sensor{};
  arsc::ArscSourceParams arsc{};     // the force loop as a feed-override source of programs (S3)
  // Circle, move and programs are refused until every axis they move is
  // homed. Off by default (the papers' runs start where the table stands at
  // power-up); a machine sets it on at commissioning (docs/safety.md).
  bool homing_required = false;
  // The spindle's ramp, at-speed window and limits (spindle.* parameters):
  // applied only while the spindle is stopped and still (TickTask::apply_config).
  SpindleParams spindle{};
  // Member by member (C++20): a field added to any part is compared too.
  bool operator==(const FirmwareConfig&) const = default;
};

// The planner's limits from a config: each axis' path limits, the
// supervisor's position limits as soft limits, the 1 ms tick.
motion::MotionLimits path_limits(const FirmwareConfig& config) noexcept;
// The member of `config` a member of `limits` = path_limits(config) comes
// from; nullptr for one that comes from no member (the tick).
const void* path_limits_source(const FirmwareConfig& config, const motion::MotionLimits& limits,
                               const void* member) noexcept;

// The papers' defaults (S1 eq. (31), Tables 1/2) with the PID baseline
// tuned by the stated rule (pid_tuning.hpp).
FirmwareConfig default_firmware_config() noexcept;

// Which part of the config is wrong and why (static text, no allocation):
// e.g. section "axis x: sliding-mode", field "q", reason "must satisfy 0 < q < 1".
struct ConfigError {
  const char* section = "";
  const char* field = "";
  const char* reason = "";  // empty when valid
  // The offending member in the config validated (nullptr: none named): the
  // CAN node's parameter table tells its parameter from it (param_table.cpp).
  const void* member = nullptr;
  bool ok() const noexcept { return reason[0] == '\0'; }
};

ConfigError validate(const FirmwareConfig& config) noexcept;
// The same, skipping the parts (an axis, the supervisor, the force loop)
// that are byte for byte those of `valid_base`, a config that passed
// validate(): a parameter change checks what it changes.
ConfigError validate(const FirmwareConfig& config, const FirmwareConfig& valid_base) noexcept;

}  // namespace tnv::fw
