#include "firmware/control/rdvsc_controller.hpp"

#include <algorithm>
#include <cmath>

#include "firmware/control/unit_saturation.hpp"

namespace tnv::fw {

namespace {
bool finite_inputs(const AxisState& x, const AxisReference& r) noexcept {
  return std::isfinite(x.position_mm) && std::isfinite(x.speed_mm_s) && std::isfinite(r.position_mm) &&
         std::isfinite(r.speed_mm_s) && std::isfinite(r.next_position_mm) && std::isfinite(r.next_speed_mm_s);
}
}  // namespace

RdvscController::RdvscController(ControllerKind kind, hal::Axis axis) noexcept
    : RdvscController(kind, paper_axis_model(axis), paper_sliding_mode_params(axis, kind)) {}

RdvscController::RdvscController(ControllerKind kind, const AxisModel& model,
                                 const SlidingModeParams& params) noexcept
    : kind_(kind), model_(model), params_(params) {
  status_ = check(params);
  if (status_.ok) apply(params);
  reset();
}

ParamCheck RdvscController::check(const SlidingModeParams& params) const noexcept {
  if (kind_ != ControllerKind::dvsc && kind_ != ControllerKind::rdvsc)
    return param_error("kind", "RdvscController implements dvsc and rdvsc only");
  SlidingModeParams p = params;
  if (kind_ == ControllerKind::dvsc) p.gamma = 0.0;
  return validate(p, model_);
}

void RdvscController::apply(const SlidingModeParams& params) noexcept {
  params_ = params;
  if (kind_ == ControllerKind::dvsc) params_.gamma = 0.0;  // DVSC+DDC: s_k = G e_k
  G_ << params_.G_position_1_s, params_.G_speed;
  GA_ = G_ * model_.A;
  GB_ = (G_ * model_.B).value();
  inv_GB_ = 1.0 / GB_;
}

ParamCheck RdvscController::set_params(const SlidingModeParams& params) noexcept {
  const ParamCheck c = check(params);
  if (!c.ok) return c;  // old parameters stay in force
  const bool was_configured = status_.ok;
  apply(params);
  status_ = c;
  if (!was_configured) {
    reset();
    return c;
  }
  // Re-form s_{k-1} with the new surface so (5) continues smoothly.
  s_prev_ = (G_ * e_prev_).value() + params_.gamma * s_prev2_;
  ddc_armed_ = false;  // the last command came from the old law
  return c;
}

void RdvscController::reset() noexcept {
  s_prev_ = 0.0;  // s_{-1}
  s_prev2_ = 0.0;
  e_prev_.setZero();
  d_hat_mm_s_ = 0.0;  // d^_{-1}
  u_law_mm_s_ = 0.0;
  u_applied_mm_s_ = 0.0;
  ddc_armed_ = false;
  signals_ = {};
}

double RdvscController::update(const AxisState& x, const AxisReference& ref) noexcept {
  if (!status_.ok || !finite_inputs(x, ref)) {
    reset();
    return 0.0;
  }
  const Eigen::Vector2d x_k(x.position_mm, x.speed_mm_s);
  const Eigen::Vector2d x_ref_k(ref.position_mm, ref.speed_mm_s);
  const Eigen::Vector2d x_ref_next(ref.next_position_mm, ref.next_speed_mm_s);
  const double q = params_.q;
  const double eta = params_.eta_mm_s;
  const double phi = params_.phi_mm_s;
  const double gamma = params_.gamma;

  const Eigen::Vector2d e_k = x_k - x_ref_k;
  // S1 eq. (5): recursive switching function
  const double s_k = (G_ * e_k).value() + gamma * s_prev_;

  if (ddc_armed_) {
    // S1 eq. (7): disturbance estimate. The last term is zero unless the
    // previous command was clamped (then it removes the unapplied part).
    const double innovation = s_k - q * s_prev_ + eta * sat_unit(s_prev_ / phi) -
                              GB_ * (u_applied_mm_s_ - u_law_mm_s_);
    d_hat_mm_s_ += inv_GB_ * params_.g * innovation;
  }

  // S1 eq. (6): control law
  const double u_law = -d_hat_mm_s_ + inv_GB_ * (-(GA_ * x_k).value() + (G_ * x_ref_next).value() - gamma * s_k + q * s_k -
                                                 eta * sat_unit(s_k / phi));
  const double u_max = params_.u_max_mm_s;
  const double u = std::clamp(u_law, -u_max, u_max);

  s_prev2_ = s_prev_;
  s_prev_ = s_k;
  e_prev_ = e_k;
  u_law_mm_s_ = u_law;
  u_applied_mm_s_ = u;
  ddc_armed_ = true;
  signals_ = {s_k, d_hat_mm_s_, u, u != u_law};
  return u;
}

}  // namespace tnv::fw
