#pragma once
// Model-based friction feed-forward (issue 7, item 3): the speed command
// that balances the reference plant's Stribeck friction at the reference
// speed, added to the axis controller's output. Off by default, so the
// papers' three controllers run untouched (Table 3).
//
//   u_ff = dir * (f_c + (f_s - f_c) exp(-(v / v_s)^2)) / K
//
// v is the reference speed over the coming tick, (v_ref,k + v_ref,k+1) / 2.
// Rule at velocity reversals: dir = sign(v); when |v| is below
// kReversalSpeed_mm_s (the reference is turning round) dir is the sign of
// the reference's change v_ref,k+1 - v_ref,k, the way it is about to move,
// so the breakaway force is there before the axis has to move; a reference
// at rest (no speed, no change) gets no feed-forward, so a holding axis is
// not pushed against its stiction.
#include "firmware/control/param_check.hpp"

namespace tnv::fw {

struct FrictionFeedForward {
  bool enabled = false;
  double coulomb_mm_s = 1.5;    // f_c, table speed equivalent
  double stiction_mm_s = 3.0;   // f_s >= f_c
  double stribeck_mm_s = 0.1;   // v_s > 0
  double gain = 1.0;            // K: table speed per commanded mm/s (> 0)
  double fraction = 1.0;        // share of the model applied, 0..1.5
  bool operator==(const FrictionFeedForward&) const = default;
};

inline constexpr double kReversalSpeed_mm_s = 1e-6;

// Finite; f_c >= 0; f_s >= f_c; v_s > 0; K > 0; 0 <= fraction <= 1.5.
ParamCheck validate(const FrictionFeedForward& ff) noexcept;

// Friction the reference plant opposes a slipping axis with at speed v
// (the Stribeck curve, without the sign): f_c + (f_s - f_c) exp(-(v/v_s)^2).
double stribeck_level_mm_s(const FrictionFeedForward& ff, double speed_mm_s) noexcept;

// u_ff for the tick from x_ref,k to x_ref,k+1 (0 when disabled).
double friction_feedforward_mm_s(const FrictionFeedForward& ff, double ref_speed_now_mm_s,
                                 double ref_speed_next_mm_s) noexcept;


}  // namespace tnv::fw
