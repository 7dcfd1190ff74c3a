#include "firmware/supervisor/motion_plausibility.hpp"

#include <cmath>

namespace tnv::fw {

PlausibilityVerdict MotionPlausibility::update(std::int64_t counts, double applied_mm_s, bool valid,
                                               const AxisModel& model, double count_mm, double full_scale_mm_s,
                                               const PlausibilityLimit& limit) noexcept {
  PlausibilityVerdict v;
  const double step_mm = static_cast<double>(counts - last_counts_) * count_mm;
  const double u_prev_mm_s = last_applied_mm_s_;
  last_counts_ = counts;
  last_applied_mm_s_ = valid ? applied_mm_s : 0.0;
  if (!valid || history_ == 0) {
    history_ = valid ? 1 : 0;  // this count is the new base; the steps before it are unknown
    return v;
  }
  // Newest first: dp_k and u_{k-1} (the command that acted over this interval).
  for (std::size_t j = steps_mm_.size() - 1; j > 0; --j) steps_mm_[j] = steps_mm_[j - 1];
  steps_mm_[0] = step_mm;
  for (std::size_t j = applied_mm_s_.size() - 1; j > 0; --j) applied_mm_s_[j] = applied_mm_s_[j - 1];
  applied_mm_s_[0] = applied_mm_s;
  const std::uint32_t steps_known = history_;  // measured steps now held, dp_k included
  if (history_ < 1 + kRunawayWindowTicks) ++history_;
  if (steps_known < 2) return v;  // dp_{k-1} not measured yet

  v.checked = true;
  const double a12 = model.A(0, 1), a22 = model.A(1, 1), b1 = model.B(0), b2 = model.B(1);
  const double c = a12 * b2 - a22 * b1;
  v.step_mm = step_mm;
  v.predicted_mm = a22 * steps_mm_[1] + b1 * applied_mm_s + c * u_prev_mm_s;
  const double quantisation_mm = static_cast<double>(kQuantisationCounts) * count_mm;
  v.spread_mm = (std::fabs(b1) + std::fabs(c)) * limit.jump_disturbance_scale * full_scale_mm_s + quantisation_mm;
  const double low_mm = std::fmin(0.0, v.predicted_mm - v.spread_mm);
  const double high_mm = std::fmax(0.0, v.predicted_mm + v.spread_mm);
  v.jump = !(step_mm >= low_mm && step_mm <= high_mm);

  // Runaway at speed (docs/safety.md "Motion plausibility"): the w held
  // over both intervals that gives dp_k; B1 + C = A12 B2 + (1 - A22) B1 is
  // the step per mm/s of steady input, > 0 for any real axis.
  const double u1 = applied_mm_s, u2 = u_prev_mm_s;  // u_{k-1}, u_{k-2}
  const double push_gain_mm = b1 + c;
  const double push_sign = u1 > 0.0 ? 1.0 : -1.0;
  // Only while the table still moves the commanded way: once it runs
  // against the command (turned, or a slower drive braking a fast move) w
  // carries the lag term (tau - tau') a and the step check above applies.
  if (push_gain_mm > 0.0 && push_sign * u1 >= limit.runaway_push_min_command_mm_s &&
      push_sign * u2 >= limit.runaway_push_min_command_mm_s && push_sign * step_mm > 0.0) {
    const double w_mm_s = (step_mm - a22 * steps_mm_[1]) / push_gain_mm;
    const double u_small = std::fmin(std::fabs(u1), std::fabs(u2));
    const double u_large = std::fmax(std::fabs(u1), std::fabs(u2));
    const double quantisation_mm_s = quantisation_mm / push_gain_mm;
    v.push_against_mm_s = -push_sign * w_mm_s;
    v.push_limit_mm_s = limit.runaway_push_fraction * u_small + quantisation_mm_s;
    // A flipped drive pushes with its own gain; beyond twice the command the
    // table was stopped, not pushed.
    const double push_max_mm_s = kRunawayPushGainMax * u_large + quantisation_mm_s;
    v.runaway_push = v.push_against_mm_s > v.push_limit_mm_s && v.push_against_mm_s < push_max_mm_s;
  }

  if (steps_known < 1 + kRunawayWindowTicks) return v;
  // One direction over the whole window, and a real command, not hunting.
  const double sign = applied_mm_s_[0] > 0.0 ? 1.0 : -1.0;
  bool one_way = true;
  for (const double u : applied_mm_s_) one_way = one_way && sign * u >= limit.runaway_min_command_mm_s;
  v.against_mm = -sign * (steps_mm_[0] - steps_mm_[kRunawayWindowTicks]);
  v.against_limit_mm = quantisation_mm + limit.runaway_margin_mm_s * model.period_s;
  v.runaway = one_way && sign * step_mm < 0.0 && v.against_mm > v.against_limit_mm;
  // A runaway pushed to a large command also leaves the jump interval; it
  // is a runaway if the tick before already sped up against the command
  // by more than the quantisation (a count jump is one step out of a steady
  // stream).
  const bool trend = -sign * (steps_mm_[1] - steps_mm_[2]) > quantisation_mm;
  if (v.runaway && v.jump && trend) v.jump = false;
  return v;
}

}  // namespace tnv::fw
