#include "firmware/control/pid_controller.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::fw {

PidController::PidController(const AxisModel& nominal, const PidParams& params) noexcept
    : model_(nominal), params_(params) {
  status_ = validate(params, model_);
  if (status_.ok) apply(params);
  reset();
}

void PidController::apply(const PidParams& params) noexcept {
  params_ = params;
  const double tf = params_.derivative_filter_tf_s;
  filter_a_ = tf / (tf + model_.period_s);
}

ParamCheck PidController::set_params(const PidParams& params) noexcept {
  const ParamCheck c = validate(params, model_);
  if (!c.ok) return c;  // old parameters stay in force
  const bool was_configured = status_.ok;
  const PidParams old = params_;
  apply(params);
  status_ = c;
  if (!was_configured) {
    reset();
  } else if (primed_ && params_.ki > 0.0) {
    // Bumpless: the integral takes up the step of the kp and kd terms.
    integral_mm_s_ += (old.kp - params_.kp) * e_prev_mm_ + (old.kd - params_.kd) * de_filtered_mm_s_;
  }
  return c;
}

void PidController::reset() noexcept {
  integral_mm_s_ = 0.0;
  e_prev_mm_ = 0.0;
  de_filtered_mm_s_ = 0.0;
  primed_ = false;
  signals_ = {};
}

double PidController::update(const AxisState& x, const AxisReference& ref) noexcept {
  const bool finite = std::isfinite(x.position_mm) && std::isfinite(ref.position_mm) &&
                      std::isfinite(ref.speed_mm_s) && std::isfinite(ref.next_speed_mm_s);
  if (!status_.ok || !finite) {
    reset();
    return 0.0;
  }
  const double period_s = model_.period_s;
  const double e_mm = ref.position_mm - x.position_mm;
  if (!primed_) {
    e_prev_mm_ = e_mm;  // no derivative kick on the first tick
    primed_ = true;
  }
  const double de_raw_mm_s = (e_mm - e_prev_mm_) / period_s;
  de_filtered_mm_s_ = filter_a_ * de_filtered_mm_s_ + (1.0 - filter_a_) * de_raw_mm_s;

  // Nominal-model inverse of the speed loop: v_{k+1} = A22 v_k + B2 u_k.
  const double u_ff =
      params_.feedforward ? (ref.next_speed_mm_s - model_.A(1, 1) * ref.speed_mm_s) / model_.B(1) : 0.0;
  const double p_term = params_.kp * e_mm;
  const double d_term = params_.kd * de_filtered_mm_s_;
  const double u_max = params_.u_max_mm_s;

  double integral = integral_mm_s_ + params_.ki * period_s * e_mm;
  double u_law = u_ff + p_term + integral + d_term;
  // Anti-windup: hold the integral while clamped and e drives further into the clamp.
  if ((u_law > u_max && e_mm > 0.0) || (u_law < -u_max && e_mm < 0.0)) {
    integral = integral_mm_s_;
    u_law = u_ff + p_term + integral + d_term;
  }
  integral_mm_s_ = integral;
  e_prev_mm_ = e_mm;

  const double u = std::clamp(u_law, -u_max, u_max);
  signals_ = {0.0, integral_mm_s_, u, u != u_law};
  return u;
}

}  // namespace tnv::fw
