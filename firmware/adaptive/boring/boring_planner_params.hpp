#pragma once
// Parameters of the adaptive boring infeed planner (S4, Lee 1983). Defaults
// are the paper's simulation (Table 1, Fig. 3): d0 = 0.1165 mm,
// sigma_d = 0.016231 mm, alpha0 = 0.5, S0 = 0.5 mm/rev, P0 = I, overhang
// 40..310 mm, phi = 60 deg.
//
// Two readings the paper leaves open are choices here (see
// docs/reproduction-s4.md for what each does):
//  - gain_form: the printed (5) divides by Sigma_k + x'Px, the printed (6)
//    by 1 + x'Px. Default normalised (1 in both: P is the covariance of the
//    estimate divided by Sigma, so "P0 = I" and "reset P = I" are relative
//    to the measurement noise).
//  - reset_count: what "three in a row" counts. Default measurements (each
//    position of each part in order); the paper's false-alarm figure
//    2e-8 = 0.0027^3 is three single measurements.
#include "firmware/control/param_check.hpp"

namespace tnv::fw {

enum class BoringGainForm {
  normalised,  // 1 in (5) and (6): Kalman filter with covariance Sigma*P
  kalman,      // Sigma in (5) and (6): P is the covariance of theta itself
  printed,     // Sigma in (5), 1 in (6), as printed (not a Kalman filter)
};

enum class BoringResetCount {
  measurements,  // consecutive out-of-band measurements, across parts
  parts,         // consecutive parts with any out-of-band measurement
  positions,     // consecutive out-of-band measurements at the same position
};

enum class BoringLogBase { natural, decimal };

const char* to_string(BoringGainForm form) noexcept;
const char* to_string(BoringResetCount count) noexcept;
const char* to_string(BoringLogBase base) noexcept;

struct BoringPlannerParams {
  double target_deflection_mm = 0.1165;  // d0 (Table 1 d_opt)
  double sigma_d_mm = 0.016231;          // measurement noise of d, 1 sigma (Table 1)
  double band_sigmas = 3.0;              // in band: |d - d0| <= band_sigmas * sigma_d
  double alpha0 = 0.5;                   // start-up guess of alpha, paper: 0 < alpha0 <= 1
  double nominal_infeed_mm_rev = 0.5;    // S0, the infeed of part 1
  double infeed_min_mm_rev = 0.005;      // the schedule is clamped to this range
  double infeed_max_mm_rev = 1.0;
  double overhang_min_mm = 40.0;         // range the model is used over (Table 1)
  double overhang_max_mm = 310.0;
  double alpha_min = 0.05;               // the schedule uses max(alpha_hat, alpha_min): 1/alpha stays bounded
  double initial_covariance = 1.0;       // P0 = p0 I; the reset sets P = p0 I too
  double force_angle_deg = 60.0;         // phi in eq. (11)
  BoringGainForm gain_form = BoringGainForm::normalised;
  BoringResetCount reset_count = BoringResetCount::measurements;
  int reset_after = 3;                   // out-of-band results in a row that reset P
  bool startup_in_rls = false;           // also feed part 1's measurements to the RLS
  BoringLogBase log_base = BoringLogBase::natural;
};

// Checks: all finite; d0 > 0; sigma_d > 0; band > 0; 0 < alpha0 <= 3;
// 0 < infeed_min < infeed_max; S0 inside the infeed range; 0 < overhang_min
// < overhang_max; 0 < alpha_min < 1; p0 > 0; 0 <= phi < 90 deg;
// 1 <= reset_after <= 100; enums valid.
ParamCheck validate(const BoringPlannerParams& params) noexcept;

}  // namespace tnv::fw
