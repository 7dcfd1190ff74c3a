#include "firmware/adaptive/arsc/faithful_arsc.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::fw::arsc {

namespace {
bool all_finite(const std::array<double, 7>& a) noexcept {
  return std::all_of(a.begin(), a.end(), [](double x) { return std::isfinite(x); });
}
}  // namespace

ParamCheck validate(const FaithfulArscConfig& c) noexcept {
  if (!all_finite(c.d_star)) return param_error("d_star", "desired coefficients must be finite");
  if (const ParamCheck p = validate(c.fixed); !p.ok) return p;
  if (!is_finite(c.initial_model)) return param_error("initial_model", "must be finite");
  if (const ParamCheck p = validate(c.rls); !p.ok) return p;
  if (const ParamCheck p = validate(c.guards); !p.ok) return p;
  if (!std::isfinite(c.force_ref) || !(c.force_ref > 0.0)) return param_error("force_ref", "must be > 0");
  if (!std::isfinite(c.u_limit) || !(c.u_limit > 0.0)) return param_error("u_limit", "must be > 0");
  return param_ok();
}

FaithfulArsc::FaithfulArsc(const FaithfulArscConfig& config) noexcept
    : config_(config), rls_(config.rls, config.initial_model) {
  reset();
}

void FaithfulArsc::reset() noexcept {
  rls_.reset(config_.initial_model);
  signals_ = ArscSignals{};
  signals_.gains = with_fixed(config_.fixed);
  f1_ = v1_ = f2_ = v2_ = u1_ = u2_ = 0.0;
}

double FaithfulArsc::step(double force, double feed) noexcept {
  ArscSignals& s = signals_;
  // MODEL_ESTIMATION: S3 eq. (5); the input applied at t-1 was computed at t-2.
  s.estimator_updated = false;
  if (s.samples > 0 && std::isfinite(force) && std::isfinite(feed))
    s.estimator_updated = rls_.update(Arv2Rls::regressor(f1_, v1_, f2_, v2_, u2_), force, feed);

  // NEXT_INPUT_GENERATION: S3 eqs. (11), (7), (10) with the gains in force.
  double u = 0.0;
  if (s.have_gains && std::isfinite(force) && std::isfinite(feed)) {
    u = std::clamp(servo_control(s.gains, s.servo, force, feed), -config_.u_limit, config_.u_limit);
    if (!std::isfinite(u)) u = 0.0;
    s.servo = servo_advance(s.gains, s.servo, force, feed, config_.force_ref);
  }

  // ARSC_GAIN_UPDATING: S3 eqs. (25), (26); the new gains act from t+1.
  const GainDesign design = solve_faithful_gains(rls_.model(), config_.d_star, config_.fixed, config_.guards);
  s.last_reason = design.reason;
  s.rcond = design.rcond;
  ++s.reason_counts[static_cast<std::size_t>(design.reason)];
  if (design.reason == GuardReason::none) {
    s.gains = design.gains;
    s.have_gains = true;
  }

  f2_ = f1_;
  v2_ = v1_;
  f1_ = force;
  v1_ = feed;
  u2_ = u1_;
  u1_ = u;
  s.u_next = u;
  ++s.samples;
  return u;
}

}  // namespace tnv::fw::arsc
