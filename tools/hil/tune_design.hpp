#pragma once
// Automatic design from an identified axis (issue 7, item 2). The rules,
// stated (docs/autotune.md gives the reasons):
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
//   shaper    none: no structural mode is identified from the table encoder
//
// Checked: fw::validate() of the whole config (the theorems' conditions
// among others) and the linearised closed loop's spectral radius < 1 on
// the identified model and, when given, on another (e.g. the true) model.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "firmware/control/pid_tuning.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tools/hil/tune_identify.hpp"

namespace tnv::hil {

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
};

AxisDesign design_axis(const AxisIdentification& id);

// Spectral radius of the linearised loop of `params` on `model` (R-DVSC+DDC).
double sliding_loop_spectral_radius(const fw::AxisModel& model, const fw::SlidingModeParams& params);

// base with the designed model, gains and friction feed-forward of both axes.
fw::FirmwareConfig apply_designs(const fw::FirmwareConfig& base, const AxisDesign& x, const AxisDesign& y);

nlohmann::json design_json(const AxisDesign& d);

}  // namespace tnv::hil
