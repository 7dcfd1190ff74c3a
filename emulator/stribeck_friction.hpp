#pragma once
// Slipping friction of one axis, as a table speed (mm/s).
// reference plant: f = sign(v) (f_c + (f_s - f_c) exp(-(v/v_s)^2))
#include <algorithm>
#include <cmath>

namespace tnv::emu {

class StribeckFriction {
 public:
  StribeckFriction(double coulomb_mm_s, double stiction_mm_s, double stribeck_mm_s) noexcept
      : coulomb_mm_s_(coulomb_mm_s),
        excess_mm_s_(stiction_mm_s - coulomb_mm_s),
        inv_stribeck_s_mm_(1.0 / stribeck_mm_s),
        neg_inv_stribeck_s_mm_(-inv_stribeck_s_mm_),
        exp_cutoff_ratio_(exp_cutoff_ratio(coulomb_mm_s, stiction_mm_s - coulomb_mm_s)),
        exp_skip_ratio_(std::min(exp_cutoff_ratio_, vanishing_ratio(coulomb_mm_s, stiction_mm_s - coulomb_mm_s, 55))) {}

  double coulomb_mm_s() const noexcept { return coulomb_mm_s_; }
  double stiction_mm_s() const noexcept { return coulomb_mm_s_ + excess_mm_s_; }

  // |f(v)| while slipping.
  double magnitude_mm_s(double speed_mm_s) const noexcept {
    const double ratio = speed_mm_s * inv_stribeck_s_mm_;
    // Beyond this the Stribeck term is below a quarter of an ulp of f_c, so
    // f_c + term == f_c exactly and exp() is skipped (6.17 v_s for f_s = 2 f_c):
    // the same bits as evaluating it, the margin covering exp's rounding.
    if (std::abs(ratio) >= exp_skip_ratio_) return coulomb_mm_s_;
    // -(v/v_s)^2 as (v * -1/v_s) (v / v_s): the same bits as -ratio * ratio
    // (a sign is exact), with the negation off the sub-step's dependency
    // chain (in the Stribeck zone each sub-step waits for the last one's exp).
    const double neg_ratio = speed_mm_s * neg_inv_stribeck_s_mm_;
    return coulomb_mm_s_ + excess_mm_s_ * std::exp(neg_ratio * ratio);
  }
  // True if |f| is exactly f_c at every speed of this sign at least this far
  // from zero (with a hair of margin for rounding).
  bool coulomb_only_beyond(double speed_mm_s) const noexcept {
    return std::abs(speed_mm_s * inv_stribeck_s_mm_) >= exp_cutoff_ratio_ * (1.0 + 1e-9);
  }
  // f(v) while slipping; f(0) = 0 (a resting axis is handled by Karnopp, not here).
  double slipping_mm_s(double speed_mm_s) const noexcept {
    return speed_mm_s == 0.0 ? 0.0 : std::copysign(magnitude_mm_s(speed_mm_s), speed_mm_s);
  }

 private:
  // Smallest |v|/v_s beyond which (f_s - f_c) exp(-(v/v_s)^2) < f_c 2^-bits
  // (2^-54: below half an ulp of f_c; 2^-55: a quarter). With f_c = 0 the
  // term only vanishes when exp underflows to zero (exp(-746) == 0).
  static double vanishing_ratio(double coulomb_mm_s, double excess_mm_s, int bits) noexcept {
    if (excess_mm_s <= 0.0) return 0.0;  // no Stribeck term at all
    if (coulomb_mm_s <= 0.0) return std::sqrt(746.0);
    const double log_ratio = std::log(excess_mm_s / coulomb_mm_s) + bits * std::log(2.0);
    return std::sqrt(std::max(log_ratio, 0.0));
  }
  // Where the closed form's "friction is exactly f_c" holds: the 2^-54 speed,
  // never below 6.5 v_s.
  static double exp_cutoff_ratio(double coulomb_mm_s, double excess_mm_s) noexcept {
    if (excess_mm_s <= 0.0) return 0.0;
    return std::max(6.5, vanishing_ratio(coulomb_mm_s, excess_mm_s, 54));
  }

  double coulomb_mm_s_;
  double excess_mm_s_;  // f_s - f_c
  double inv_stribeck_s_mm_;
  double neg_inv_stribeck_s_mm_;
  double exp_cutoff_ratio_;
  double exp_skip_ratio_;  // <= exp_cutoff_ratio_
};

}  // namespace tnv::emu
