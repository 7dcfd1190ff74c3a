#include "firmware/compensation/screw_compensation.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::fw {

namespace {

// A reference step smaller than this is no motion: a holding reference
// keeps its last direction.
constexpr double kMotionStep_mm = 1e-9;

double lead_offset_mm(const ScrewCompensation& c, double reference_mm) noexcept {
  const double lead = c.lead_um_per_m * 1e-6;
  return reference_mm / (1.0 + lead) - reference_mm;
}

}  // namespace

ParamCheck validate(const ScrewCompensation& c) noexcept {
  if (!std::isfinite(c.backlash_mm)) return param_error("backlash_mm", "must be finite (NaN or inf given)");
  if (!std::isfinite(c.backlash_rate_mm_s)) return param_error("backlash_rate_mm_s", "must be finite (NaN or inf given)");
  if (!std::isfinite(c.lead_um_per_m)) return param_error("lead_um_per_m", "must be finite (NaN or inf given)");
  if (!(c.backlash_mm >= 0.0 && c.backlash_mm <= 0.2)) return param_error("backlash_mm", "must be 0 .. 0.2 mm");
  if (!(c.backlash_rate_mm_s >= 0.01 && c.backlash_rate_mm_s <= 100.0))
    return param_error("backlash_rate_mm_s", "must be 0.01 .. 100 mm/s");
  if (!(std::fabs(c.lead_um_per_m) <= 1000.0)) return param_error("lead_um_per_m", "must be -1000 .. 1000 um/m");
  return param_ok();
}

bool same(const ScrewCompensation& a, const ScrewCompensation& b) noexcept {
  return a.backlash_mm == b.backlash_mm && a.backlash_rate_mm_s == b.backlash_rate_mm_s &&
         a.lead_um_per_m == b.lead_um_per_m;
}

ScrewCompensator::Offsets ScrewCompensator::advance(const ScrewCompensation& c, double reference_mm,
                                                    double next_reference_mm, double tick_s) noexcept {
  const double step_mm = next_reference_mm - reference_mm;
  if (step_mm > kMotionStep_mm) direction_ = 1;
  if (step_mm < -kMotionStep_mm) direction_ = -1;
  const double target_mm = 0.5 * c.backlash_mm * direction_;
  const double max_change_mm = c.backlash_rate_mm_s * tick_s;
  const double now_backlash_mm = backlash_offset_mm_;
  backlash_offset_mm_ += std::clamp(target_mm - backlash_offset_mm_, -max_change_mm, max_change_mm);
  Offsets o;
  o.now_mm = now_backlash_mm + lead_offset_mm(c, reference_mm);
  o.next_mm = backlash_offset_mm_ + lead_offset_mm(c, next_reference_mm);
  next_offset_mm_ = o.next_mm;
  return o;
}

}  // namespace tnv::fw
