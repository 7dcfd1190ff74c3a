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

// The motor-side offset for the table-side reference x_ref, given the
// backlash offset: p0 - e_turn(p0) - x_ref (screw_compensation.hpp).
double offset_mm(const ScrewCompensation& c, double reference_mm, double backlash_offset_mm) noexcept {
  const double to_p0_mm = backlash_offset_mm + lead_offset_mm(c, reference_mm);
  return to_p0_mm - turn_error_mm(c, reference_mm + to_p0_mm);
}

}  // namespace

double turn_error_mm(const ScrewCompensation& c, double motor_mm) noexcept {
  // Position in table points, wrapped into [0, 16): floor keeps it exact for negative positions.
  const double points = motor_mm / c.turn_period_mm * static_cast<double>(kTurnErrorPoints);
  const double wrapped = points - std::floor(points / static_cast<double>(kTurnErrorPoints)) *
                                      static_cast<double>(kTurnErrorPoints);
  const double below = std::floor(wrapped);
  const double frac = wrapped - below;
  const std::size_t j = static_cast<std::size_t>(below) % kTurnErrorPoints;  // wrapped == 16.0 by rounding: 0
  const std::size_t k = (j + 1) % kTurnErrorPoints;
  return c.turn_error_mm[j] * (1.0 - frac) + c.turn_error_mm[k] * frac;
}

ParamCheck validate(const ScrewCompensation& c) noexcept {
  if (!std::isfinite(c.backlash_mm))
    return param_error(&c.backlash_mm, "backlash_mm", "must be finite (NaN or inf given)");
  if (!std::isfinite(c.backlash_rate_mm_s))
    return param_error(&c.backlash_rate_mm_s, "backlash_rate_mm_s", "must be finite (NaN or inf given)");
  if (!std::isfinite(c.lead_um_per_m))
    return param_error(&c.lead_um_per_m, "lead_um_per_m", "must be finite (NaN or inf given)");
  if (!(c.backlash_mm >= 0.0 && c.backlash_mm <= 0.2))
    return param_error(&c.backlash_mm, "backlash_mm", "must be 0 .. 0.2 mm");
  if (!(c.backlash_rate_mm_s >= 0.01 && c.backlash_rate_mm_s <= 100.0))
    return param_error(&c.backlash_rate_mm_s, "backlash_rate_mm_s", "must be 0.01 .. 100 mm/s");
  if (!(std::fabs(c.lead_um_per_m) <= 1000.0))
    return param_error(&c.lead_um_per_m, "lead_um_per_m", "must be -1000 .. 1000 um/m");
  if (!std::isfinite(c.turn_period_mm))
    return param_error(&c.turn_period_mm, "turn_period_mm", "must be finite (NaN or inf given)");
  if (!(c.turn_period_mm >= 0.1 && c.turn_period_mm <= 1000.0))
    return param_error(&c.turn_period_mm, "turn_period_mm", "must be 0.1 .. 1000 mm");
  for (const double& e_mm : c.turn_error_mm) {
    if (!std::isfinite(e_mm)) return param_error(&e_mm, "turn_error_mm", "must be finite (NaN or inf given)");
    if (!(std::fabs(e_mm) <= 0.1))
      return param_error(&e_mm, "turn_error_mm", "must be -0.1 .. 0.1 mm (-100 .. 100 um)");
  }
  return param_ok();
}

ScrewCompensator::Offsets ScrewCompensator::advance(const ScrewCompensation& c, double reference_mm,
                                                    double next_reference_mm, double tick_s) noexcept {
  const double step_mm = next_reference_mm - reference_mm;
  if (step_mm > kMotionStep_mm) direction_ = 1;
  if (step_mm < -kMotionStep_mm) direction_ = -1;
  // Compensation off (the common case): the formulae below give exactly +0
  // for both offsets; skip their divisions (a hot path of every tick).
  if (c.backlash_mm == 0.0 && backlash_offset_mm_ == 0.0 && c.lead_um_per_m == 0.0 &&
      std::ranges::all_of(c.turn_error_mm, [](double e_mm) { return e_mm == 0.0; })) {
    next_offset_mm_ = 0.0;
    return Offsets{};
  }
  const double target_mm = 0.5 * c.backlash_mm * direction_;
  const double max_change_mm = c.backlash_rate_mm_s * tick_s;
  const double now_backlash_mm = backlash_offset_mm_;
  backlash_offset_mm_ += std::clamp(target_mm - backlash_offset_mm_, -max_change_mm, max_change_mm);
  Offsets o;
  o.now_mm = offset_mm(c, reference_mm, now_backlash_mm);
  o.next_mm = offset_mm(c, next_reference_mm, backlash_offset_mm_);
  next_offset_mm_ = o.next_mm;
  return o;
}

}  // namespace tnv::fw
