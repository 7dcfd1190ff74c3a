#pragma once
// The model's prediction of a frequency-response experiment: the plant as
// an exact 1 ms zero-order-hold model and the active controller
// linearised (firmware/control/linear_controller.hpp, loop_analysis.hpp's
// convention L = -K P).
//
// Two views of the loop:
//  - design (loop_analysis.hpp): the controller fed the model's state
//    [p, v]; what the design rules assume;
//  - implemented: the controller fed [p_k, (p_k - p_{k-1}) / T], the
//    encoder position and the M-method speed the tick actually uses,
//    around the plant model given. This is the loop a measurement sees.
#include <complex>
#include <vector>

#include "firmware/control/axis_model.hpp"
#include "firmware/control/linear_controller.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tools/tune/bode_margins.hpp"
#include "tools/tune/freq_response.hpp"

namespace tnv::tune {

struct LoopModel {
  fw::AxisModel plant;              // the plant (exact ZOH of the table, or the config's model)
  fw::LinearController controller;  // the active controller, linearised
  bool measured_speed = true;       // implemented view (true) or design view (false)
};

// The active controller of an axis config, linearised: PID, or DVSC+DDC /
// R-DVSC+DDC inside the boundary layer (DVSC: gamma = 0), on the config's model.
fw::LinearController active_linear_controller(const fw::AxisConfig& axis);

// Position response of the plant to the speed command: [1 0] (zI - A)^{-1} B.
std::complex<double> plant_response(const fw::AxisModel& plant, double freq_hz) noexcept;
// L(z) of the loop model; T = L / (1 + L); the plant for LoopKind::plant.
std::complex<double> model_response(const LoopModel& model, LoopKind kind, double freq_hz) noexcept;
// model_response at each frequency, coherence 1.
std::vector<ResponsePoint> model_points(const LoopModel& model, LoopKind kind, const std::vector<double>& freqs_hz);

struct ModelMargins {
  BodeMargins margins;
  double bandwidth_hz = 0.0;
};
// margins_from_points / bandwidth_hz on a dense log grid 0.05 Hz .. Nyquist.
ModelMargins model_margins(const LoopModel& model);

}  // namespace tnv::tune
