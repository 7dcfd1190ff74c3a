#include "firmware/adaptive/boring/infeed_schedule.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tnv::fw {

InfeedCommand optimal_infeed(const BoringTheta& theta, double overhang_mm, const BoringPlannerParams& p) noexcept {
  InfeedCommand out;
  if (!std::isfinite(overhang_mm) || overhang_mm < p.overhang_min_mm || overhang_mm > p.overhang_max_mm) {
    out.check = param_error("overhang_mm", "must be finite and within [overhang_min_mm, overhang_max_mm]");
    return out;
  }
  if (!theta.allFinite()) {
    out.check = param_error("theta", "estimate is not finite");
    return out;
  }
  const double alpha = std::max(theta(1), p.alpha_min);
  out.alpha_limited = theta(1) < p.alpha_min;
  // S4 eq. (3) in natural logs: ln S = (ln d0 - ln C - beta ln L) / alpha.
  const double ln_c = ln_of_base(p.log_base) * theta(0);
  const double ln_s = (std::log(p.target_deflection_mm) - ln_c - theta(2) * std::log(overhang_mm)) / alpha;
  const double ln_min = std::log(p.infeed_min_mm_rev);
  const double ln_max = std::log(p.infeed_max_mm_rev);
  out.infeed_limited = !(ln_s >= ln_min && ln_s <= ln_max);
  out.infeed_mm_rev = std::exp(std::clamp(ln_s, ln_min, ln_max));  // a NaN ln_s cannot happen: theta is finite
  return out;
}

double infeed_along_overhang_mm_rev(double overhang_mm, double l1_mm, double s1_mm_rev, double l2_mm,
                                    double s2_mm_rev) noexcept {
  if (!(overhang_mm > 0.0 && l1_mm > 0.0 && l2_mm > 0.0 && s1_mm_rev > 0.0 && s2_mm_rev > 0.0) || l1_mm == l2_mm)
    return std::numeric_limits<double>::quiet_NaN();
  const double slope = std::log(s2_mm_rev / s1_mm_rev) / std::log(l2_mm / l1_mm);
  return s1_mm_rev * std::pow(overhang_mm / l1_mm, slope);
}

double InfeedAlongOverhang::at(double overhang_mm) const noexcept {
  const double lo = l1_mm < l2_mm ? l1_mm : l2_mm;
  const double hi = l1_mm < l2_mm ? l2_mm : l1_mm;
  const double l = overhang_mm < lo ? lo : (overhang_mm > hi ? hi : overhang_mm);  // NaN stays NaN
  return infeed_along_overhang_mm_rev(l, l1_mm, s1_mm_rev, l2_mm, s2_mm_rev);
}

}  // namespace tnv::fw
