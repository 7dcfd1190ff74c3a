#include "firmware/adaptive/arsc/cutting_gain_rls.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::fw::arsc {

ParamCheck validate(const CuttingGainRlsParams& p) noexcept {
  const double all[] = {p.a21,      p.initial_gain,       p.gain_min,       p.gain_max,
                        p.forgetting, p.initial_covariance, p.max_covariance, p.min_feed};
  for (double x : all)
    if (!std::isfinite(x)) return param_error("cutting_gain_rls", "every field must be finite");
  if (!(std::fabs(p.a21) < 1.0)) return param_error("a21", "must satisfy |a21| < 1 (a stable force process)");
  if (!(p.gain_min > 0.0 && p.gain_min < p.gain_max)) return param_error("gain_min", "must satisfy 0 < min < max");
  if (!(p.initial_gain >= p.gain_min && p.initial_gain <= p.gain_max))
    return param_error("initial_gain", "must lie in [gain_min, gain_max]");
  if (!(p.forgetting > 0.0 && p.forgetting <= 1.0)) return param_error("forgetting", "must satisfy 0 < lambda <= 1");
  if (!(p.initial_covariance > 0.0 && p.initial_covariance <= p.max_covariance))
    return param_error("initial_covariance", "must satisfy 0 < P0 <= max_covariance");
  if (!(p.min_feed > 0.0)) return param_error("min_feed", "must be > 0");
  return param_ok();
}

bool CuttingGainRls::update(double force, double force_prev, double feed_prev) noexcept {
  if (!(std::isfinite(force) && std::isfinite(force_prev) && std::isfinite(feed_prev))) return false;
  if (!(std::fabs(feed_prev) >= params_.min_feed)) return false;
  const double y = force + params_.a21 * force_prev;  // S3 eq. (28): g v(t-1)
  const double denominator = params_.forgetting + feed_prev * feed_prev * covariance_;
  const double k = covariance_ * feed_prev / denominator;
  gain_ = std::clamp(gain_ + k * (y - gain_ * feed_prev), params_.gain_min, params_.gain_max);
  covariance_ = std::min(covariance_ / denominator, params_.max_covariance);
  return true;
}

}  // namespace tnv::fw::arsc
