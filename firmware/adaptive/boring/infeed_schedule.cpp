#include "firmware/adaptive/boring/infeed_schedule.hpp"

#include <algorithm>

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

}  // namespace tnv::fw
