#include "firmware/adaptive/arsc/outer_arsc.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::fw::arsc {

namespace {

FeedForceModel unit_gain(FeedForceModel m) noexcept {
  m.cutting_gain = 1.0;
  return m;
}

// The estimator works on g per sample: f(t) - a f(t-1) = (1 - a) g vbar(t-1)
// (S3 eq. 28 over one period with the mean feed), a = exp(-T / T_f).
CuttingGainRlsParams estimator_params(const OuterArscConfig& c) noexcept {
  const double a = std::exp(-c.period_s / c.model.force_time_constant_s);
  const double per_sample = 1.0 - a;
  CuttingGainRlsParams p;
  p.a21 = -a;
  p.initial_gain = per_sample * c.model.cutting_gain;
  p.gain_min = per_sample * c.gain_min;
  p.gain_max = per_sample * c.gain_max;
  p.forgetting = std::exp(-c.period_s / c.memory_s);
  p.initial_covariance = c.initial_covariance;
  p.max_covariance = c.max_covariance;
  p.min_feed = c.min_feed_mm_s / c.feed_scale_mm_s;
  return p;
}

bool positive_finite(double x) noexcept { return std::isfinite(x) && x > 0.0; }

}  // namespace

ParamCheck validate(const OuterArscConfig& c) noexcept {
  if (!positive_finite(c.period_s)) return param_error("period_s", "must be > 0");
  if (const ParamCheck p = validate(c.model); !p.ok) return p;
  if (!(c.model.command_delay_s <= c.period_s))
    return param_error("command_delay_s", "must be <= period_s (one delay state)");
  if (const ParamCheck p = validate(c.poles); !p.ok) return p;
  if (const ParamCheck p = validate(c.limits); !p.ok) return p;
  if (!positive_finite(c.force_scale_n)) return param_error("force_scale_n", "must be > 0");
  if (!positive_finite(c.feed_scale_mm_s)) return param_error("feed_scale_mm_s", "must be > 0");
  if (!std::isfinite(c.force_ref_n) || !(c.force_ref_n >= 0.0)) return param_error("force_ref_n", "must be >= 0");
  if (!std::isfinite(c.feed_min_mm_s) || !std::isfinite(c.feed_max_mm_s) || !(c.feed_min_mm_s < c.feed_max_mm_s))
    return param_error("feed_min_mm_s", "must be finite and < feed_max_mm_s");
  if (!positive_finite(c.memory_s)) return param_error("memory_s", "must be > 0");
  if (!(positive_finite(c.gain_min) && std::isfinite(c.gain_max) && c.gain_min < c.gain_max))
    return param_error("gain_min", "must satisfy 0 < gain_min < gain_max");
  if (!(c.model.cutting_gain >= c.gain_min && c.model.cutting_gain <= c.gain_max))
    return param_error("cutting_gain", "must lie in [gain_min, gain_max]");
  if (!positive_finite(c.min_feed_mm_s)) return param_error("min_feed_mm_s", "must be > 0");
  return validate(estimator_params(c));
}

OuterArsc::OuterArsc(const OuterArscConfig& config) noexcept
    : config_(config),
      unit_plant_(discretise(unit_gain(config.model), config.period_s)),
      gain_per_sample_(1.0 - std::exp(-config.period_s / config.model.force_time_constant_s)),
      estimator_(estimator_params(config)) {
  reset();
}

void OuterArsc::reset() noexcept {
  estimator_.reset();
  signals_ = OuterArscSignals{};
  f1_ = u1_ = 0.0;
  history_ = false;
  range_lo_ = config_.feed_min_mm_s / config_.feed_scale_mm_s;
  range_hi_ = config_.feed_max_mm_s / config_.feed_scale_mm_s;
  design();  // the test stage's model gives gains before the first sample
}

void OuterArsc::restart() noexcept {
  OuterArscSignals& s = signals_;
  s.eta = 0.0;
  s.command_mm_s = 0.0;
  s.clamped = false;
  s.estimator_updated = false;
  f1_ = u1_ = 0.0;
  history_ = false;  // the next sample does not update the estimator from the old force history
}

bool OuterArsc::set_feed_range_mm_s(double lo_mm_s, double hi_mm_s) noexcept {
  if (!(std::isfinite(lo_mm_s) && std::isfinite(hi_mm_s) && lo_mm_s <= hi_mm_s)) return false;
  if (lo_mm_s < config_.feed_min_mm_s || hi_mm_s > config_.feed_max_mm_s) return false;
  range_lo_ = lo_mm_s / config_.feed_scale_mm_s;
  range_hi_ = hi_mm_s / config_.feed_scale_mm_s;
  return true;
}

bool OuterArsc::set_force_ref_n(double force_ref_n) noexcept {
  if (!std::isfinite(force_ref_n) || !(force_ref_n >= 0.0)) return false;
  config_.force_ref_n = force_ref_n;
  return true;
}

double OuterArsc::cutting_gain_n_per_mm_s() const noexcept {
  return estimator_.gain() / gain_per_sample_ * config_.force_scale_n / config_.feed_scale_mm_s;
}

SampledFeedForce OuterArsc::plant_at(double g) const noexcept {
  SampledFeedForce p = unit_plant_;
  p.phi(0, 1) *= g;  // feed -> force
  p.gamma0(0) *= g;
  p.gamma1(0) *= g;
  return p;
}

void OuterArsc::design() noexcept {
  const double g = estimator_.gain() / gain_per_sample_;
  const OuterDesign d = solve_outer_gains(plant_at(g), config_.period_s, config_.poles, config_.limits);
  signals_.last_reason = d.reason;
  signals_.rcond = d.rcond;
  ++signals_.reason_counts[static_cast<std::size_t>(d.reason)];
  if (d.reason == GuardReason::none) {
    signals_.gains = d.gains;
    signals_.have_gains = true;
  }
}

double OuterArsc::step(double force_n, double feed_mm_s, double mean_feed_mm_s) noexcept {
  OuterArscSignals& s = signals_;
  if (!(std::isfinite(force_n) && std::isfinite(feed_mm_s) && std::isfinite(mean_feed_mm_s))) {
    s.estimator_updated = false;
    return s.command_mm_s;  // hold the last command: a bad reading moves nothing
  }
  const double f = force_n / config_.force_scale_n;
  const double v = feed_mm_s / config_.feed_scale_mm_s;
  const double v_mean = mean_feed_mm_s / config_.feed_scale_mm_s;
  const double f_ref = config_.force_ref_n / config_.force_scale_n;

  // Estimation: S3 eq. (28) over the period that just ended, g only.
  s.estimator_updated = config_.adapt && history_ && estimator_.update(f, f1_, v_mean);

  // Next input: S3 eq. (11) with the command in flight, clamped to the feed range.
  double u = 0.0;
  s.clamped = false;
  if (s.have_gains) {
    const OuterGains& g = s.gains;
    const double u_law = g.k * s.eta + g.gamma31 * f + g.gamma32 * v + g.gamma33 * u1_;
    u = std::isfinite(u_law) ? std::clamp(u_law, range_lo_, range_hi_) : std::clamp(u1_, range_lo_, range_hi_);
    const double d_eta = config_.period_s * (f - f_ref);  // S3 eq. (7), in seconds
    const double excess = u_law - u;
    s.clamped = excess != 0.0;  // also true for a non-finite law (held at u(t-1))
    // Anti-windup: integrate unless the clamp is on and integrating pushes further out.
    if (!(s.clamped && g.k * d_eta * excess > 0.0)) s.eta += d_eta;
  }
  s.clamped_samples += s.clamped ? 1u : 0u;

  // Gain update from the new estimate, used from the next sample.
  design();

  f1_ = f;
  u1_ = u;
  history_ = true;
  s.command_mm_s = u * config_.feed_scale_mm_s;
  ++s.samples;
  return s.command_mm_s;
}

}  // namespace tnv::fw::arsc
