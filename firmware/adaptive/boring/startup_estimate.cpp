#include "firmware/adaptive/boring/startup_estimate.hpp"

namespace tnv::fw {

StartupEstimate startup_estimate(std::span<const DeflectionSample> samples, double alpha0,
                                 BoringLogBase base) noexcept {
  StartupEstimate out;
  if (samples.size() < 2) {
    out.check = param_error("measurements", "start-up needs at least two positions (eq. (10))");
    return out;
  }
  double sum_v = 0.0;
  double sum_u = 0.0;
  for (const DeflectionSample& s : samples) {
    if (!std::isfinite(s.deflection_mm) || !(s.deflection_mm > 0.0)) {
      out.check = param_error("deflection_mm", "start-up needs finite deflections > 0");
      return out;
    }
    if (!std::isfinite(s.infeed_mm_rev) || !(s.infeed_mm_rev > 0.0)) {
      out.check = param_error("infeed_mm_rev", "must be finite and > 0");
      return out;
    }
    if (!std::isfinite(s.overhang_mm) || !(s.overhang_mm > 0.0)) {
      out.check = param_error("overhang_mm", "must be finite and > 0");
      return out;
    }
    sum_u += model_log(s.deflection_mm, base) - alpha0 * model_log(s.infeed_mm_rev, base);
    sum_v += model_log(s.overhang_mm, base);
  }
  const double n = static_cast<double>(samples.size());
  const double mean_u = sum_u / n;
  const double mean_v = sum_v / n;
  double svv = 0.0;
  double svu = 0.0;
  for (const DeflectionSample& s : samples) {
    const double v = model_log(s.overhang_mm, base) - mean_v;
    const double u = model_log(s.deflection_mm, base) - alpha0 * model_log(s.infeed_mm_rev, base) - mean_u;
    svv += v * v;
    svu += v * u;
  }
  if (!(svv > 1e-12)) {
    out.check = param_error("overhang_mm", "start-up needs two different overhangs (eq. (10))");
    return out;
  }
  const double beta0 = svu / svv;              // S4 eq. (10): beta0 = log(d1/d2) / log(L1/L2)
  const double log_c0 = mean_u - beta0 * mean_v;  // S4 eq. (10): C0 = d1 / (S0^alpha0 L1^beta0)
  out.theta = BoringTheta(log_c0, alpha0, beta0);
  return out;
}

}  // namespace tnv::fw
