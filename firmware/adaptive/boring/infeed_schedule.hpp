#pragma once
// The optimal infeed for constant deflection d0 (S4 eq. (3)):
//   S_opt(L) = (d0 / (C L^beta))^(1/alpha)
// from the current estimate, with alpha held at or above alpha_min (so
// 1/alpha stays bounded) and S clamped to the configured infeed range.
#include "firmware/adaptive/boring/log_model.hpp"
#include "firmware/control/param_check.hpp"

namespace tnv::fw {

struct InfeedCommand {
  ParamCheck check;            // !ok: infeed_mm_rev is 0, do not cut
  double infeed_mm_rev = 0.0;  // S to cut with at this overhang
  bool infeed_limited = false; // eq. (3) asked for more or less than the range
  bool alpha_limited = false;  // alpha_hat < alpha_min, alpha_min used
};

// theta in the params' log base. Errors: overhang not finite or outside
// [overhang_min_mm, overhang_max_mm]; theta not finite.
InfeedCommand optimal_infeed(const BoringTheta& theta, double overhang_mm, const BoringPlannerParams& params) noexcept;

// The infeed along the depth of a pass from the two the node told, S1 at
// L1 and S2 at L2: eq. (3) with the planner's estimates is the line
//   S(L) = S1 (L / L1)^(ln(S2 / S1) / ln(L2 / L1))
// in log S, log L through them (its alpha and beta are the estimates';
// the infeed range's clamp aside). All > 0, L1 != L2; NaN otherwise.
double infeed_along_overhang_mm_rev(double overhang_mm, double l1_mm, double s1_mm_rev, double l2_mm,
                                    double s2_mm_rev) noexcept;

// The node's infeed along the depth of the pass being cut: the infeeds it
// told for this part, S1 at L1 (top gauge) and S2 at L2 (bottom), and
// infeed_along_overhang_mm_rev() between them. Outside [L1, L2] (the
// approach above the top gauge, the overrun below the bottom one) the
// overhang is held at the nearer end: the model's range (BoringStationSettings).
struct InfeedAlongOverhang {
  double l1_mm = 0.0;
  double s1_mm_rev = 0.0;
  double l2_mm = 0.0;
  double s2_mm_rev = 0.0;

  // S at this overhang (mm/rev); NaN while unset or invalid (a feed from it does not move).
  double at(double overhang_mm) const noexcept;
};

}  // namespace tnv::fw
