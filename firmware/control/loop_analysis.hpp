#pragma once
// Frequency-domain and pole analysis of "axis model + LinearController",
// loop broken at the plant input (configuration time only: complex
// arithmetic and small loops, no allocation, no exceptions).
//   P(z) = (zI - A)^{-1} B,  K(z) = Cc (zI - Ac)^{-1} Bc + Dc,  L(z) = -K(z) P(z)
// so that the closed loop is 1 + L(z) = 0 (negative-feedback convention).
#include <array>
#include <complex>

#include "firmware/control/axis_model.hpp"
#include "firmware/control/linear_controller.hpp"

namespace tnv::fw {

std::complex<double> loop_gain(const AxisModel& model, const LinearController& controller,
                               double omega_rad_s) noexcept;

struct LoopMargins {
  bool crossover_found = false;
  int crossover_count = 0;             // |L| = 1 crossings between 0.1 rad/s and Nyquist
  double crossover_rad_s = 0.0;        // the highest-frequency |L| = 1 crossing
  double phase_margin_deg = 0.0;       // smallest over all crossings, in (-180, 180]
  double gain_margin_db = 0.0;         // gain increase to instability (phase crossings with |L| < 1); inf if none
  double phase_crossover_rad_s = 0.0;  // where gain_margin_db was taken
  double gain_reduction_margin_db = 0.0;  // gain decrease to instability (phase crossings with |L| > 1); inf if none
};

// Scans 0.1 rad/s .. pi/T (Nyquist included) on a log grid and refines
// every crossing by bisection.
LoopMargins loop_margins(const AxisModel& model, const LinearController& controller) noexcept;

// Closed-loop poles of [x; xi]_{k+1} = [A + B Dc, B Cc; Bc, Ac] [x; xi].
using ClosedLoopPoles = std::array<std::complex<double>, 5>;
ClosedLoopPoles closed_loop_poles(const AxisModel& model, const LinearController& controller) noexcept;
double spectral_radius(const ClosedLoopPoles& poles) noexcept;

}  // namespace tnv::fw
