#include "firmware/adaptive/arsc/feed_force_model.hpp"

#include <cmath>

namespace tnv::fw::arsc {

namespace {

// expm1(x) / x, 1 at x = 0 (no cancellation for small x).
double expm1_ratio(double x) noexcept { return std::fabs(x) < 1e-12 ? 1.0 : std::expm1(x) / x; }

// Constant input over [0, h]: x(h) = M x(0) + N u.
struct Interval {
  Eigen::Matrix2d m;
  Eigen::Vector2d n;
};

Interval interval(const FeedForceModel& p, double h) noexcept {
  const double a_f = std::exp(-h / p.force_time_constant_s);
  const double a_v = std::exp(-h / p.drive_time_constant_s);
  // Force response to the initial feed: (1/T_f) int_0^h exp(-(h - s)/T_f) exp(-s/tau_v) ds.
  const double c = 1.0 / p.force_time_constant_s - 1.0 / p.drive_time_constant_s;
  const double i_v = (h / p.force_time_constant_s) * a_f * expm1_ratio(h * c);
  Interval out;
  out.m << a_f, p.cutting_gain * i_v, 0.0, a_v;
  out.n << p.cutting_gain * (1.0 - a_f - i_v), 1.0 - a_v;
  return out;
}

}  // namespace

ParamCheck validate(const FeedForceModel& m) noexcept {
  if (!(std::isfinite(m.force_time_constant_s) && std::isfinite(m.drive_time_constant_s) &&
        std::isfinite(m.command_delay_s) && std::isfinite(m.cutting_gain)))
    return param_error("feed_force_model", "every field must be finite");
  if (!(m.force_time_constant_s > 0.0)) return param_error("force_time_constant_s", "must be > 0");
  if (!(m.drive_time_constant_s > 0.0)) return param_error("drive_time_constant_s", "must be > 0");
  if (!(m.command_delay_s >= 0.0)) return param_error("command_delay_s", "must be >= 0");
  if (!(m.cutting_gain > 0.0)) return param_error("cutting_gain", "must be > 0 (feed makes force)");
  return param_ok();
}

SampledFeedForce discretise(const FeedForceModel& model, double period_s) noexcept {
  const double theta = model.command_delay_s < period_s ? model.command_delay_s : period_s;
  const Interval before = interval(model, theta);         // the previous command still acts
  const Interval after = interval(model, period_s - theta);  // this sample's command
  SampledFeedForce s;
  s.phi = after.m * before.m;  // = M(T): the intervals compose
  s.gamma1 = after.m * before.n;
  s.gamma0 = after.n;
  s.force_pole = std::exp(-period_s / model.force_time_constant_s);
  s.drive_pole = std::exp(-period_s / model.drive_time_constant_s);
  return s;
}

}  // namespace tnv::fw::arsc
