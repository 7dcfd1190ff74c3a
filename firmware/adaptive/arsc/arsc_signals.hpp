#pragma once
// What one ARSC sample did, for telemetry and plots (both variants).
#include <array>
#include <cstdint>

#include "firmware/adaptive/arsc/arsc_gains.hpp"
#include "firmware/adaptive/arsc/gain_guard.hpp"
#include "firmware/adaptive/arsc/servo_law.hpp"

namespace tnv::fw::arsc {

struct ArscSignals {
  double u_next = 0.0;         // computed at t, applied from t+1 (normalised)
  ArscGains gains{};           // in force for this sample's control
  bool have_gains = false;     // false until the first good design
  bool estimator_updated = false;
  GuardReason last_reason = GuardReason::none;  // of this sample's gain update
  ServoState servo{};
  double rcond = 0.0;          // of this sample's gain equations
  std::uint32_t samples = 0;
  std::array<std::uint32_t, kGuardReasonCount> reason_counts{};  // per GuardReason, updates refused/accepted
};

}  // namespace tnv::fw::arsc
