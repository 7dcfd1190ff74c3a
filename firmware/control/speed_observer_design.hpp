#pragma once
// Off-line design of the speed observer's gain (speed_observer.hpp): the
// steady-state Kalman gain of the augmented axis model, from stated noise
// levels. Runs on the host (tune_design) or between ticks, never per tick
// (it iterates the Riccati equation).
//
//   P = Phi P Phi^T - Phi P C^T (C P C^T + R)^-1 C P Phi^T + Q      (DARE, a-priori P)
//   L = P C^T (C P C^T + R)^-1                                         (filter gain)
//   Q = diag(0, sigma_v^2, sigma_d^2),  R = q_enc^2 / 12                (uniform rounding)
//
// sigma_v: unmodelled change of the speed per tick (mm/s), sigma_d: change
// of the lumped disturbance d per tick (mm/s; friction at a reversal,
// cutting), q_enc: one encoder count (mm).
#include "firmware/control/axis_model.hpp"
#include "firmware/control/speed_observer.hpp"

namespace tnv::fw {

struct ObserverNoise {
  double speed_mm_s = 0.0;        // sigma_v per tick
  double disturbance_mm_s = 0.0;  // sigma_d per tick
  double count_mm = 10.0 / 24000.0;
};

struct ObserverDesign {
  bool ok = false;
  SpeedObserverParams params{};  // gains set, enabled = false
  int iterations = 0;
  double innovation_variance_mm2 = 0.0;  // C P C^T + R at convergence
};

ObserverDesign steady_state_kalman_gain(const AxisModel& model, const ObserverNoise& noise) noexcept;

}  // namespace tnv::fw
