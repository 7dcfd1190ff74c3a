#include "firmware/adaptive/arsc/robust_arsc.hpp"

#include <algorithm>
#include <cmath>

#include "firmware/adaptive/arsc/faithful_gain_solve.hpp"

namespace tnv::fw::arsc {

ParamCheck validate(const RobustArscConfig& c) noexcept {
  for (double d : c.d_star)
    if (!std::isfinite(d)) return param_error("d_star", "desired coefficients must be finite");
  if (const ParamCheck p = validate(c.fixed); !p.ok) return p;
  if (const ParamCheck p = validate(c.drive); !p.ok) return p;
  if (const ParamCheck p = validate(c.estimator); !p.ok) return p;
  if (const ParamCheck p = validate(c.gain_trend); !p.ok) return p;
  if (const ParamCheck p = validate(c.limits); !p.ok) return p;
  if (!std::isfinite(c.force_ref) || !(c.force_ref > 0.0)) return param_error("force_ref", "must be > 0");
  if (!std::isfinite(c.u_limit) || !(c.u_limit > 0.0)) return param_error("u_limit", "must be > 0");
  return param_ok();
}

RobustArsc::RobustArsc(const RobustArscConfig& config) noexcept
    : config_(config), estimator_(config.estimator), trend_(config.gain_trend) {
  reset();
}

bool RobustArsc::set_force_ref(double force_ref) noexcept {
  if (!std::isfinite(force_ref) || !(force_ref > 0.0)) return false;
  config_.force_ref = force_ref;
  return true;
}

StructuredModel RobustArsc::model() const noexcept {
  return StructuredModel{config_.drive, config_.estimator.a21, estimator_.gain()};
}

void RobustArsc::design() noexcept {
  ArscSignals& s = signals_;
  const StructuredModel m{config_.drive, config_.estimator.a21, design_gain_};
  const RobustDesign d = solve_robust_gains(m, config_.d_star, config_.fixed, config_.limits);
  s.last_reason = d.reason;
  s.rcond = d.rcond;
  ++s.reason_counts[static_cast<std::size_t>(d.reason)];
  if (d.reason == GuardReason::none) {
    s.gains = d.gains;
    s.have_gains = true;
  }
}

void RobustArsc::reset() noexcept {
  estimator_.reset();
  trend_.reset();
  design_gain_ = estimator_.gain();
  signals_ = ArscSignals{};
  signals_.gains = with_fixed(config_.fixed);
  f1_ = v1_ = 0.0;
  design();  // the pre-identified model gives gains before the first sample
}

double RobustArsc::step(double force, double feed) noexcept {
  ArscSignals& s = signals_;
  const bool measured = std::isfinite(force) && std::isfinite(feed);
  // Estimation: S3 eq. (28) for g only.
  s.estimator_updated = s.samples > 0 && measured && estimator_.update(force, f1_, v1_);

  // Next input: S3 eqs. (11), (7), (10).
  double u = 0.0;
  if (s.have_gains && measured) {
    const double u_law = servo_control(s.gains, s.servo, force, feed);
    u = std::clamp(u_law, -config_.u_limit, config_.u_limit);
    if (!std::isfinite(u)) u = 0.0;
    const double eta = s.servo.eta;
    s.servo = servo_advance(s.gains, s.servo, force, feed, config_.force_ref);
    if (u != u_law) s.servo.eta = eta;  // clamped: do not wind up
  }

  // Gain update from the new estimate, used from t+1.
  if (s.estimator_updated)
    design_gain_ = trend_.update(estimator_.gain(), config_.estimator.gain_min, config_.estimator.gain_max);
  design();

  f1_ = measured ? force : f1_;
  v1_ = measured ? feed : v1_;
  s.u_next = u;
  ++s.samples;
  return u;
}

}  // namespace tnv::fw::arsc
