#pragma once
// The spindle-deflection model in log form (S4 eqs. (2), (4), (7)):
//   d = C S^alpha L^beta                       (2)
//   y = log d,  x = (1, log S, log L),  theta = (log C, alpha, beta)
//   y = x' theta + v                           (4), (7)
// "log" is natural by default; the paper does not say which, so the base
// is a parameter (a decimal log rescales x and y, which changes what
// P0 = I means).
#include <Eigen/Core>
#include <cmath>

#include "firmware/adaptive/boring/boring_planner_params.hpp"

namespace tnv::fw {

using BoringTheta = Eigen::Vector3d;       // (log C, alpha, beta)
using BoringRegressor = Eigen::Vector3d;   // (1, log S, log L)
using BoringCovariance = Eigen::Matrix3d;  // P, eq. (8)

inline double ln_of_base(BoringLogBase base) noexcept {
  return base == BoringLogBase::decimal ? 2.302585092994046 : 1.0;
}

inline double model_log(double value, BoringLogBase base) noexcept { return std::log(value) / ln_of_base(base); }

// S4 eq. (7): x_k = (1, log S_k, log L_k).
inline BoringRegressor boring_regressor(double infeed_mm_rev, double overhang_mm, BoringLogBase base) noexcept {
  return {1.0, model_log(infeed_mm_rev, base), model_log(overhang_mm, base)};
}

// S4 eq. (2): d = C S^alpha L^beta, evaluated from theta.
inline double model_deflection_mm(const BoringTheta& theta, double infeed_mm_rev, double overhang_mm,
                                  BoringLogBase base) noexcept {
  return std::exp(ln_of_base(base) * theta(0) + theta(1) * std::log(infeed_mm_rev) +
                  theta(2) * std::log(overhang_mm));
}

// Var(log d) for measurement noise sigma_d around d0 (first order):
// Sigma = (sigma_d / d0)^2 in natural-log units, divided by ln(b)^2 for base b.
inline double log_noise_variance(double sigma_d_mm, double d0_mm, BoringLogBase base) noexcept {
  const double r = sigma_d_mm / d0_mm / ln_of_base(base);
  return r * r;
}

}  // namespace tnv::fw
