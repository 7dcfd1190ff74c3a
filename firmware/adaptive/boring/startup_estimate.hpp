#pragma once
// Start-up from the first part, cut at the nominal infeed S0 and measured
// at two or more overhangs (S4 eqs. (9), (10)): alpha0 is a guess, beta0
// and C0 are the least-squares line through log d - alpha0 log S over
// log L. With two positions at one infeed this is eq. (10) exactly:
//   beta0 = log(d1/d2) / log(L1/L2),  C0 = d1 / (S0^alpha0 L1^beta0).
#include <span>

#include "firmware/adaptive/boring/log_model.hpp"
#include "firmware/control/param_check.hpp"

namespace tnv::fw {

struct DeflectionSample {
  double overhang_mm = 0.0;
  double infeed_mm_rev = 0.0;
  double deflection_mm = 0.0;
};

struct StartupEstimate {
  ParamCheck check;
  BoringTheta theta = BoringTheta::Zero();  // (log C0, alpha0, beta0) in the given base
};

// Errors: fewer than 2 samples; a deflection, infeed or overhang not finite
// and > 0; all overhangs (nearly) equal.
StartupEstimate startup_estimate(std::span<const DeflectionSample> samples, double alpha0,
                                 BoringLogBase base) noexcept;

}  // namespace tnv::fw
