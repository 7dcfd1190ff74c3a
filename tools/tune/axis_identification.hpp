#pragma once
// Plant identification for auto-tuning: the fit of the records the
// firmware's own open-loop excitation (fw::ExcitationGenerator, run by the
// tick task) leaves on one axis, on the host. Where the records come from
// (the HIL rig: tools/hil/tune_identify.hpp; a node over CAN:
// tools/can/can_identify.hpp) does not matter here.
//
//   steps  at +-U1, +-U2: p(t) = p0 + V (t - tau (1 - e^{-t/tau}))  -> tau, V
//          (the speed loop tau dv/dt = K u - f_c sign(v) - v from rest)
//          V = K U - sign(U) f_c over the four steps                 -> K, f_c
//   ramps  +- (slow): the DAC command at the first tick the encoder
//          moves is the breakaway level f_s / K                      -> f_s
//   mode   the steps' tool-side accelerometer samples, when present: the
//          ringing after each pulse (mode_fit.hpp)                   -> f, zeta
//
// Not identified: the Stribeck speed v_s (the Stribeck branch has a
// negative slope, an open-loop axis jumps across it). The encoder cannot
// see a structural mode (it deflects the tool, not the table): the mode
// comes from the accelerometer only. friction_feedforward_from() feeds
// Coulomb friction only (the reason is given there).
#include <string>
#include <vector>

#include "firmware/compensation/friction_feedforward.hpp"
#include "firmware/control/axis_model.hpp"
#include "hal/axis.hpp"
#include "tools/tune/mode_fit.hpp"

namespace tnv::tune {

inline constexpr double kAssumedStribeck_mm_s = 0.1;

struct StepRecord {
  double level_mm_s = 0.0;            // the command the DAC applied (quantised)
  std::vector<double> position_mm;    // encoder position at the ticks after the step started: p(jT), j = 0..n
  // Tool-side accelerometer at the ticks j = 0.. from the step start through
  // the settle (longer than position_mm); empty: no accelerometer.
  std::vector<double> accel_mm_s2;
};

struct RampRecord {
  double breakaway_mm_s = 0.0;  // DAC-quantised command of the tick before the first count moved
  bool broke_away = false;
};

struct StepFit {
  double tau_s = 0.0;
  double speed_mm_s = 0.0;  // V
  double rms_residual_mm = 0.0;
};

// Least squares over tau (coarse log grid, then golden section), p0 and V linear.
StepFit fit_step(const std::vector<double>& position_mm, double period_s);

struct AxisIdentification {
  bool ok = false;
  std::string error;
  hal::Axis axis = hal::Axis::x;
  double tau_s = 0.0;
  double gain = 0.0;
  double coulomb_mm_s = 0.0;
  double stiction_mm_s = 0.0;
  fw::AxisModel model{};             // zero-order hold of (tau, K) at 1 ms
  std::vector<StepFit> steps;        // one per step record
  std::vector<StepRecord> step_records;
  std::vector<RampRecord> ramps;
  // Structural mode from the tool-side accelerometer (mode_fit.hpp); only
  // looked for when the step records carry accelerometer samples.
  bool mode_found = false;
  double mode_hz = 0.0;
  double mode_zeta = 0.0;
  ModeFit mode_fit{};
};

// The fit from the records (the same on the emulator and over CAN).
AxisIdentification identify_from_records(hal::Axis axis, const std::vector<StepRecord>& steps,
                                         const std::vector<RampRecord>& ramps, double period_s);

fw::FrictionFeedForward friction_feedforward_from(const AxisIdentification& id);

}  // namespace tnv::tune
