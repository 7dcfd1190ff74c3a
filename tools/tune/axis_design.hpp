#pragma once
// Automatic design from an identified axis. The rules, stated
// (docs/autotune.md gives the reasons):
//
//   model     A, B = exact 1 ms zero-order hold of the identified (tau, K)
//   G         [c_G / tau, 1], c_G = 1.5            (S1 eq. 5; the papers'
//             X and Y have G_p tau = 1.54 and 1.45)
//   q         0.9                                   (S1 eq. 4; the papers' X)
//   g         0.3                                   (S1 eq. 7; d~ pole 1 - g, Theorem 1)
//   eta       the papers' eta scaled by the model's GB: eta = eta_0 GB / GB_0,
//             eta_0 = 0.4 mm/s at GB_0 of the reference X model, so the
//             reaching step (eta/GB in command) is the same speed command
//             on every table (Theorem 2 needs eta > |GB d~|)
//   phi       10 eta / (q + 1)                      (Theorem 2: phi > eta/(q+1))
//   gamma     0.5 min(1 - g, q)                     (Theorem 5 / Remark 2:
//             0 < gamma < min(1 - g, q); the papers use 0.49 and 0.44 of it)
//   PID       tune_pid_equal_crossover on the identified model with the
//             designed DVSC+DDC (gamma = 0) (firmware/control/pid_tuning.hpp)
//   friction  Coulomb feed-forward from the identified f_c and K
//             (friction_feedforward_from: the stiction/Stribeck part is
//             left to the DDC, see there)
//   shaper    ZVD at the mode identified from the tool-side accelerometer,
//             none without one (shaper_choice.hpp says why)
//   observer  steady-state Kalman gain on the identified model augmented with
//             a constant disturbance (fw::steady_state_kalman_gain), noise
//             per tick sigma_v = kObserverSpeedNoise_mm_s, sigma_d =
//             kObserverDisturbanceNoise_mm_s, R = one count^2 / 12; the
//             identified Coulomb friction f_c / K taken out of its model
//             (dead band kObserverFrictionDeadband_mm_s); on, the estimated
//             speed fed back (speed_observer.hpp, docs/autotune.md)
//
// Checked: fw::validate() of the whole config (the theorems' conditions
// among others) and the linearised closed loop's spectral radius < 1 on
// the identified model and, when given, on another (e.g. the true) model.
#include <string>

#include "firmware/control/pid_tuning.hpp"
#include "firmware/control/speed_observer_design.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tools/tune/axis_identification.hpp"
#include "tools/tune/shaper_choice.hpp"

namespace tnv::tune {

struct AxisDesign {
  bool ok = false;
  std::string error;
  fw::AxisModel model{};
  fw::SlidingModeParams sliding{};
  fw::PidParams pid{};
  fw::PidTuningReport pid_report{};
  fw::FrictionFeedForward friction{};
  double rdvsc_spectral_radius = 0.0;  // linearised R-DVSC+DDC on the identified model
  double dvsc_spectral_radius = 0.0;
  double pid_spectral_radius = 0.0;
  fw::ObserverNoise observer_noise{};  // the stated noise the observer gain is designed for
  fw::SpeedObserverParams observer{};  // speed observer, enabled by the rule
  ShaperChoice shaper{};               // x.shaper.* / y.shaper.*: ZVD at the identified mode, or none
};

// The observer rule's noise levels (per 1 ms tick).
inline constexpr double kObserverSpeedNoise_mm_s = 0.2;
inline constexpr double kObserverDisturbanceNoise_mm_s = 1.0;
inline constexpr double kObserverFrictionDeadband_mm_s = 0.02;

// The observer of the rule above for `model` and `noise`; ok false if the
// Riccati iteration did not give a stable observer.
fw::ObserverDesign design_observer(const fw::AxisModel& model, const fw::ObserverNoise& noise);

AxisDesign design_axis(const AxisIdentification& id);

// Spectral radius of the linearised loop of `params` on `model` (R-DVSC+DDC).
double sliding_loop_spectral_radius(const fw::AxisModel& model, const fw::SlidingModeParams& params);

// base with the designed model, gains and friction feed-forward of both axes.
fw::FirmwareConfig apply_designs(const fw::FirmwareConfig& base, const AxisDesign& x, const AxisDesign& y);

}  // namespace tnv::tune
