#pragma once
// The operator jog's limits per axis (motion/jog_producer.hpp runs the jog).
#include "firmware/control/param_check.hpp"

namespace tnv::fw {

struct JogLimits {
  double speed_max_mm_s = 50.0;
  double accel_mm_s2 = 1000.0;  // the jog's path acceleration at most (the planner's limits apply too)
  double deadman_s = 0.1;       // longest silence of the operator stream before the jog stops
  bool operator==(const JogLimits&) const = default;
};

// Checks: all finite and > 0.
ParamCheck validate(const JogLimits& limits) noexcept;

}  // namespace tnv::fw
