#include "tools/tune/loop_prediction.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "firmware/control/linear_controller.hpp"
#include "firmware/control/loop_analysis.hpp"
#include "firmware/control/matrix_poles.hpp"

namespace tnv::tune {

namespace {

LoopPrediction from_controller(const fw::AxisModel& model, const fw::LinearController& controller) {
  LoopPrediction out;
  const fw::ClosedLoopPoles poles = fw::closed_loop_poles(model, controller);
  out.poles.assign(poles.begin(), poles.end());
  out.spectral_radius = fw::spectral_radius(poles);
  out.ok = std::isfinite(out.spectral_radius);
  if (!out.ok) out.why = "the closed-loop poles are not finite";
  return out;
}

}  // namespace

LoopPrediction predict_sliding(const fw::AxisModel& model, const fw::SlidingModeParams& p) {
  if (const fw::ParamCheck c = fw::validate(p, model); !c.ok) {
    LoopPrediction out;
    out.why = std::string(c.field) + ": " + c.reason;
    return out;
  }
  return from_controller(model, fw::linearised_sliding_mode(model, p));
}

LoopPrediction predict_pid(const fw::AxisModel& model, const fw::PidParams& p) {
  if (const fw::ParamCheck c = fw::validate(p, model); !c.ok) {
    LoopPrediction out;
    out.why = std::string(c.field) + ": " + c.reason;
    return out;
  }
  return from_controller(model, fw::linear_pid(model, p.kp, p.ki, p.kd, p.derivative_filter_tf_s));
}

LoopPrediction predict_observer(const fw::AxisModel& model, const fw::SpeedObserverParams& p) {
  LoopPrediction out;
  if (p.gain_position == 0.0 && p.gain_speed_1_s == 0.0 && p.gain_disturbance_1_s == 0.0) {
    out.why = "no gains";  // no observer (its poles would sit at 1)
    return out;
  }
  // Roots of det(zI - M) = z^3 + c2 z^2 + c1 z + c0: the companion matrix' eigenvalues.
  const fw::ObserverPolynomial c = fw::observer_error_polynomial(p, model);
  Eigen::Matrix3d companion;
  companion << -c.c2, -c.c1, -c.c0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0;
  const fw::MatrixPoles<3> roots = fw::matrix_poles<3>(companion);
  out.poles.assign(roots.begin(), roots.end());
  for (const std::complex<double>& z : out.poles) out.spectral_radius = std::max(out.spectral_radius, std::abs(z));
  out.ok = std::isfinite(out.spectral_radius);
  if (!out.ok) out.why = "the observer poles are not finite";
  return out;
}

}  // namespace tnv::tune
