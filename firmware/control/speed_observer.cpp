#include "firmware/control/speed_observer.hpp"

#include <cmath>

namespace tnv::fw {

Eigen::Matrix3d observer_phi(const AxisModel& model) noexcept {
  Eigen::Matrix3d phi;
  phi << model.A(0, 0), model.A(0, 1), model.B(0),  //
      model.A(1, 0), model.A(1, 1), model.B(1),     //
      0.0, 0.0, 1.0;
  return phi;
}

Eigen::Vector3d observer_gamma(const AxisModel& model) noexcept { return {model.B(0), model.B(1), 0.0}; }

ObserverPolynomial observer_error_polynomial(const SpeedObserverParams& params, const AxisModel& model) noexcept {
  const Eigen::Vector3d l(params.gain_position, params.gain_speed_1_s, params.gain_disturbance_1_s);
  Eigen::RowVector3d c(1.0, 0.0, 0.0);
  const Eigen::Matrix3d m = (Eigen::Matrix3d::Identity() - l * c) * observer_phi(model);
  ObserverPolynomial poly;
  // det(zI - M) = z^3 - tr(M) z^2 + (sum of principal 2x2 minors) z - det(M)
  poly.c2 = -m.trace();
  poly.c1 = m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0) + m(0, 0) * m(2, 2) - m(0, 2) * m(2, 0) + m(1, 1) * m(2, 2) -
            m(1, 2) * m(2, 1);
  const double det = m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) -
                    m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0)) +
                    m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
  poly.c0 = -det;
  // Jury's test for z^3 + c2 z^2 + c1 z + c0: P(1) > 0, P(-1) < 0, |c0| < 1,
  // |c0^2 - 1| > |c0 c2 - c1|.
  const double p_plus = 1.0 + poly.c2 + poly.c1 + poly.c0;
  const double p_minus = -1.0 + poly.c2 - poly.c1 + poly.c0;
  poly.stable = p_plus > 0.0 && p_minus < 0.0 && std::fabs(poly.c0) < 1.0 &&
                std::fabs(poly.c0 * poly.c0 - 1.0) > std::fabs(poly.c0 * poly.c2 - poly.c1);
  return poly;
}

ParamCheck validate(const SpeedObserverParams& params, const AxisModel& model) noexcept {
  struct Field {
    const char* name;
    const double* value;
  };
  const Field fields[] = {{"gain_position", &params.gain_position},
                          {"gain_speed_1_s", &params.gain_speed_1_s},
                          {"gain_disturbance_1_s", &params.gain_disturbance_1_s},
                          {"friction_mm_s", &params.friction_mm_s},
                          {"friction_deadband_mm_s", &params.friction_deadband_mm_s}};
  for (const Field& f : fields)
    if (!std::isfinite(*f.value)) return param_error(f.value, f.name, "must be finite (NaN or inf given)");
  if (!(params.friction_mm_s >= 0.0)) return param_error(&params.friction_mm_s, "friction_mm_s", "must be >= 0");
  if (!(params.friction_deadband_mm_s > 0.0))
    return param_error(&params.friction_deadband_mm_s, "friction_deadband_mm_s", "must be > 0");
  if (!is_finite(model)) return param_error(&model.B(1), "model", "A and B must be finite");
  if (!params.enabled) return param_ok();  // the zero default gains are not an observer; unused while off
  if (!observer_error_polynomial(params, model).stable)
    return param_error(&params.gain_position, "gain_position",
                       "observer error dynamics (I - L C) Phi not stable with these gains");
  return param_ok();
}

void SpeedObserver::configure(const AxisModel& model, const SpeedObserverParams& params) noexcept {
  phi_ = observer_phi(model);
  gam_ = observer_gamma(model);
  gain_ << params.gain_position, params.gain_speed_1_s, params.gain_disturbance_1_s;
  friction_mm_s_ = params.friction_mm_s;
  deadband_mm_s_ = params.friction_deadband_mm_s;
  params_ = params;
}

void SpeedObserver::reset(double position_mm, double speed_mm_s) noexcept { z_ << position_mm, speed_mm_s, 0.0; }

void SpeedObserver::update(double measured_position_mm, double applied_command_mm_s) noexcept {
  double friction_mm_s = 0.0;  // f_{k-1} = f_c/K sgn_eps(v^_{k-1})
  if (z_(1) > deadband_mm_s_) friction_mm_s = friction_mm_s_;
  if (z_(1) < -deadband_mm_s_) friction_mm_s = -friction_mm_s_;
  const Eigen::Vector3d predicted = phi_ * z_ + gam_ * (applied_command_mm_s - friction_mm_s);  // z^-_k
  z_ = predicted + gain_ * (measured_position_mm - predicted(0));             // z^_k
}

}  // namespace tnv::fw
