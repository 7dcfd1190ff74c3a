#pragma once
// The stated tuning rule for the PID baseline ("equal loop crossover with
// DVSC+DDC on the nominal model", reference-plant.md). Configuration time
// only: not for the tick.
//
// RULE (exactly what tune_pid_equal_crossover does):
//  1. Linearise DVSC+DDC (S1 eqs. (5)-(7), gamma as given: 0 for DVSC+DDC)
//     inside the boundary layer, sat(s/phi) = s/phi, on the nominal model
//     (the paper's A, B). The controller is the dynamic system from x_k to
//     u_k with states s_{k-1}, d^_{k-1} (linear_controller.hpp).
//  2. Break its loop at the plant input: L(z) = -K(z) (zI - A)^{-1} B. Take
//     its gain crossover w_c (|L| = 1, highest if several) and its phase
//     margin PM_dvsc.
//  3. Target phase margin PM* = min(PM_dvsc, 60 deg) (the cap keeps the
//     derivative gain and the measurement-noise gain sensible; the paper's X
//     and Y loops have 62 and 66 deg, so both are capped).
//  4. PID on position, same nominal plant, position measured:
//       C(z) = kp + ki T z/(z-1) + kd (1-a)(z-1)/(T (z-a)),
//     Ziegler-Nichols shape Ti = 4 Td (ki = kp/Ti, kd = kp Td), derivative
//     filter off by default (tf = Td/N if N > 0; off matches DVSC+DDC, which
//     uses the same unfiltered M-method speed).
//     Td: the smallest Td with arg(C(w_c) P(w_c)) = -180 deg + PM* (the
//     phase at w_c does not depend on kp); kp: |C(w_c) P(w_c)| = 1.
//     If PM* cannot be reached (possible only with a derivative filter), Td
//     maximises the phase margin at w_c and phase_margin_reached is false.
//  5. Verify: PID loop margins (crossover, PM, gain margins) and all
//     closed-loop poles inside the unit circle.
#include "firmware/control/axis_model.hpp"
#include "firmware/control/pid_params.hpp"
#include "firmware/control/sliding_mode_params.hpp"

namespace tnv::fw {

struct PidTuningOptions {
  double ti_over_td = 4.0;             // Ziegler-Nichols shape
  double derivative_filter_n = 0.0;    // tf = Td / N; 0 = no filter
  double max_phase_margin_deg = 60.0;  // cap on the matched phase margin
};

struct PidTuningReport {
  bool ok = false;       // solved, PM reached, PID closed loop stable, gains finite and > 0
  const char* rule = "";
  const char* note = "";  // what happened, e.g. the cap or why it failed

  // PID gains (pid_params.hpp units)
  double kp = 0.0;  // 1/s
  double ki = 0.0;  // 1/s^2
  double kd = 0.0;  // dimensionless
  double derivative_filter_tf_s = 0.0;
  double ti_s = 0.0;
  double td_s = 0.0;

  // DVSC+DDC loop (linearised, nominal model)
  double dvsc_crossover_rad_s = 0.0;
  double dvsc_crossover_hz = 0.0;
  double dvsc_phase_margin_deg = 0.0;
  double dvsc_gain_margin_db = 0.0;
  double dvsc_closed_loop_spectral_radius = 0.0;

  // PID loop (nominal model)
  double pid_crossover_rad_s = 0.0;
  double pid_crossover_hz = 0.0;
  double pid_phase_margin_deg = 0.0;
  double pid_gain_margin_db = 0.0;            // gain increase to instability
  double pid_gain_reduction_margin_db = 0.0;  // gain decrease to instability (inf if none)
  double pid_closed_loop_spectral_radius = 0.0;
  bool pid_closed_loop_stable = false;

  double target_phase_margin_deg = 0.0;
  bool phase_margin_capped = false;
  bool phase_margin_reached = false;
};

PidTuningReport tune_pid_equal_crossover(const AxisModel& nominal, const SlidingModeParams& dvsc_params,
                                         const PidTuningOptions& options = {}) noexcept;

// The tuned gains as PID parameters (feed-forward on).
PidParams pid_params_from(const PidTuningReport& report, double u_max_mm_s = kDacFullScaleSpeed_mm_s) noexcept;

// tune_pid_equal_crossover(paper_axis_model(axis), paper_dvsc_params(axis)).
PidTuningReport paper_pid_tuning(hal::Axis axis) noexcept;

// pid_params_from(paper_pid_tuning(axis), u_max): the papers' default gains,
// as that tuning computes them (bit for bit on x86-64; a test recomputes
// them), without its ~17,000 loop-gain evaluations, which were a seventh of
// the instructions of a whole-process HIL circle (docs/performance.md).
PidParams paper_pid_params(hal::Axis axis, double u_max_mm_s = kDacFullScaleSpeed_mm_s) noexcept;

}  // namespace tnv::fw
