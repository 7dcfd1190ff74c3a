#include "firmware/adaptive/boring/boring_planner_params.hpp"

#include <cmath>

namespace tnv::fw {

const char* to_string(BoringGainForm form) noexcept {
  switch (form) {
    case BoringGainForm::normalised: return "normalised";
    case BoringGainForm::kalman: return "kalman";
    case BoringGainForm::printed: return "printed";
  }
  return "?";
}

const char* to_string(BoringResetCount count) noexcept {
  switch (count) {
    case BoringResetCount::measurements: return "measurements";
    case BoringResetCount::parts: return "parts";
    case BoringResetCount::positions: return "positions";
  }
  return "?";
}

const char* to_string(BoringLogBase base) noexcept {
  switch (base) {
    case BoringLogBase::natural: return "natural";
    case BoringLogBase::decimal: return "decimal";
  }
  return "?";
}

ParamCheck validate(const BoringPlannerParams& p) noexcept {
  struct Field {
    const char* name;
    double value;
  };
  const Field fields[] = {{"target_deflection_mm", p.target_deflection_mm},
                          {"sigma_d_mm", p.sigma_d_mm},
                          {"band_sigmas", p.band_sigmas},
                          {"alpha0", p.alpha0},
                          {"nominal_infeed_mm_rev", p.nominal_infeed_mm_rev},
                          {"infeed_min_mm_rev", p.infeed_min_mm_rev},
                          {"infeed_max_mm_rev", p.infeed_max_mm_rev},
                          {"overhang_min_mm", p.overhang_min_mm},
                          {"overhang_max_mm", p.overhang_max_mm},
                          {"alpha_min", p.alpha_min},
                          {"initial_covariance", p.initial_covariance},
                          {"force_angle_deg", p.force_angle_deg}};
  for (const Field& f : fields)
    if (!std::isfinite(f.value)) return param_error(f.name, "must be finite (NaN or inf given)");
  if (!(p.target_deflection_mm > 0.0)) return param_error("target_deflection_mm", "must be > 0");
  if (!(p.sigma_d_mm > 0.0)) return param_error("sigma_d_mm", "must be > 0");
  if (!(p.band_sigmas > 0.0)) return param_error("band_sigmas", "must be > 0");
  if (!(p.alpha0 > 0.0 && p.alpha0 <= 3.0)) return param_error("alpha0", "must satisfy 0 < alpha0 <= 3");
  if (!(p.infeed_min_mm_rev > 0.0)) return param_error("infeed_min_mm_rev", "must be > 0");
  if (!(p.infeed_max_mm_rev > p.infeed_min_mm_rev))
    return param_error("infeed_max_mm_rev", "must be > infeed_min_mm_rev");
  if (!(p.nominal_infeed_mm_rev >= p.infeed_min_mm_rev && p.nominal_infeed_mm_rev <= p.infeed_max_mm_rev))
    return param_error("nominal_infeed_mm_rev", "must lie in [infeed_min_mm_rev, infeed_max_mm_rev]");
  if (!(p.overhang_min_mm > 0.0)) return param_error("overhang_min_mm", "must be > 0");
  if (!(p.overhang_max_mm > p.overhang_min_mm)) return param_error("overhang_max_mm", "must be > overhang_min_mm");
  if (!(p.alpha_min > 0.0 && p.alpha_min < 1.0)) return param_error("alpha_min", "must satisfy 0 < alpha_min < 1");
  if (!(p.initial_covariance > 0.0)) return param_error("initial_covariance", "must be > 0");
  if (!(p.force_angle_deg >= 0.0 && p.force_angle_deg < 90.0))
    return param_error("force_angle_deg", "must satisfy 0 <= phi < 90 deg (eq. (11) divides by cos phi)");
  if (p.gain_form != BoringGainForm::normalised && p.gain_form != BoringGainForm::kalman &&
      p.gain_form != BoringGainForm::printed)
    return param_error("gain_form", "unknown value");
  if (p.reset_count != BoringResetCount::measurements && p.reset_count != BoringResetCount::parts &&
      p.reset_count != BoringResetCount::positions)
    return param_error("reset_count", "unknown value");
  if (p.log_base != BoringLogBase::natural && p.log_base != BoringLogBase::decimal)
    return param_error("log_base", "unknown value");
  if (!(p.reset_after >= 1 && p.reset_after <= 100)) return param_error("reset_after", "must be in [1, 100]");
  return param_ok();
}

}  // namespace tnv::fw
