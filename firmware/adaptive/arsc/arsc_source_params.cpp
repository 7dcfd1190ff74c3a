#include "firmware/adaptive/arsc/arsc_source_params.hpp"

#include <cmath>

#include "firmware/adaptive/arsc/outer_arsc.hpp"
#include "firmware/motion/motion_interpolator.hpp"

namespace tnv::fw::arsc {

namespace {

bool arsc_finite_positive(double x) noexcept { return std::isfinite(x) && x > 0.0; }

}  // namespace

OuterArscConfig outer_config(const ArscSourceParams& p) noexcept {
  OuterArscConfig c;
  c.period_s = kArscTickS * static_cast<double>(p.period_ticks);
  c.model.force_time_constant_s = p.force_time_constant_s;
  c.model.drive_time_constant_s = p.drive_time_constant_s;
  // The override set at a sample moves the path point in that very tick;
  // the table answers from the next one (FeedForceModel's theta).
  c.model.command_delay_s = kArscTickS;
  c.model.cutting_gain = p.cutting_gain_n_per_mm_s * kArscFeedScaleMmS / kArscForceScaleN;
  c.poles.force_s = {std::complex<double>{p.pole_re_rad_s, p.pole_im_rad_s},
                     std::complex<double>{p.pole_re_rad_s, -p.pole_im_rad_s}};
  c.limits.max_gain = kArscMaxGain;
  c.force_scale_n = kArscForceScaleN;
  c.feed_scale_mm_s = kArscFeedScaleMmS;
  c.force_ref_n = p.force_ref_n;
  c.feed_min_mm_s = 0.0;
  c.feed_max_mm_s = kArscFeedCapMmS;
  c.memory_s = p.memory_s;
  c.gain_min = p.gain_min_ratio * c.model.cutting_gain;
  c.gain_max = p.gain_max_ratio * c.model.cutting_gain;
  c.adapt = p.adapt;
  return c;
}

ParamCheck validate(const ArscSourceParams& p) noexcept {
  if (!std::isfinite(p.force_ref_n) || !(p.force_ref_n >= 0.0))
    return param_error(&p.force_ref_n, "force_ref_n", "must be >= 0");
  if (p.period_ticks < 1 || p.period_ticks > kMaxArscPeriodTicks)
    return param_error(&p.period_ticks, "period_ticks", "must be 1 .. 500 ticks");
  if (!std::isfinite(p.pole_re_rad_s) || !(p.pole_re_rad_s < 0.0))
    return param_error(&p.pole_re_rad_s, "pole_re_rad_s", "must be < 0 (a stable force loop)");
  if (!std::isfinite(p.pole_im_rad_s) || !(p.pole_im_rad_s >= 0.0))
    return param_error(&p.pole_im_rad_s, "pole_im_rad_s", "must be >= 0");
  if (!arsc_finite_positive(p.force_time_constant_s))
    return param_error(&p.force_time_constant_s, "force_time_constant_s", "must be > 0");
  if (!arsc_finite_positive(p.cutting_gain_n_per_mm_s))
    return param_error(&p.cutting_gain_n_per_mm_s, "cutting_gain_n_per_mm_s", "must be > 0");
  if (!arsc_finite_positive(p.drive_time_constant_s))
    return param_error(&p.drive_time_constant_s, "drive_time_constant_s", "must be > 0");
  if (!arsc_finite_positive(p.memory_s)) return param_error(&p.memory_s, "memory_s", "must be > 0");
  if (!(arsc_finite_positive(p.gain_min_ratio) && p.gain_min_ratio <= 1.0))
    return param_error(&p.gain_min_ratio, "gain_min_ratio", "must satisfy 0 < gain_min_ratio <= 1");
  if (!(std::isfinite(p.gain_max_ratio) && p.gain_max_ratio >= 1.0))
    return param_error(&p.gain_max_ratio, "gain_max_ratio", "must be >= 1");
  if (!(std::isfinite(p.override_min) && p.override_min >= 0.0))
    return param_error(&p.override_min, "override_min", "must be >= 0");
  if (!(std::isfinite(p.override_max) && p.override_max <= motion::kMaxFeedOverride))
    return param_error(&p.override_max, "override_max", "must be <= 1.5");
  if (!(p.override_min < p.override_max))
    return param_error(&p.override_min, "override_min", "must be below override_max");
  if (!std::isfinite(p.soft_start_s) || !(p.soft_start_s >= 0.0))
    return param_error(&p.soft_start_s, "soft_start_s", "must be >= 0");
  const OuterArscConfig c = outer_config(p);
  if (const ParamCheck check = validate(c); !check.ok) return check;
  // The loop must have gains at the model it starts from (poles far too fast
  // for the period ask for gains beyond kArscMaxGain).
  const OuterDesign d = solve_outer_gains(discretise(c.model, c.period_s), c.period_s, c.poles, c.limits);
  if (d.reason != GuardReason::none)
    return param_error(&p.pole_re_rad_s, "pole_re_rad_s", "no gains for these poles at this model and period");
  return param_ok();
}

}  // namespace tnv::fw::arsc
