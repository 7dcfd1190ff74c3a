#include "emulator/axis_plant.hpp"

#include <algorithm>

#include "emulator/substep_timing.hpp"

namespace tnv::emu {

AxisPlant::AxisPlant(const AxisPlantParams& params) noexcept
    : tau_s_(params.tau_s),
      gain_(params.gain),
      friction_(params.coulomb_mm_s, params.stiction_mm_s, params.stribeck_mm_s),
      // coulomb = stiction = 0 turns friction off: no Karnopp, never stuck.
      friction_enabled_(params.stiction_mm_s > 0.0),
      accel_limit_mm_s2_(params.accel_limit_mm_s2),
      accel_limited_(params.accel_limit_mm_s2 > 0.0),
      substep_(decay_for(kSubstep_s)) {
  decay_sums_[0] = 0.0;
  for (std::size_t k = 0; k < kMaxBlock; ++k)
    decay_sums_[k + 1] = decay_sums_[k] + std::exp(-static_cast<double>(k) * kSubstep_s / tau_s_);
}

AxisPlant::Decay AxisPlant::decay_for(double duration_s) const noexcept {
  const double x = duration_s / tau_s_;
  const double decay = std::exp(-x);
  // x - (1 - e^{-x}) = sum_{n>=2} (-x)^n / n!, summed directly for small x,
  // where the difference would lose most of its digits.
  double excess = x + std::expm1(-x);
  if (x < 0.5) {
    excess = 0.0;
    double term = -x;  // (-x)^1 / 1!
    for (int n = 2; n < 40 && term != 0.0; ++n) {
      term *= -x / n;
      excess += term;
    }
  }
  return Decay{.decay = decay,
               .rise = 1.0 - decay,
               .tau_rise_s = -tau_s_ * std::expm1(-x),  // expm1: accurate for dt << tau
               .drive_gain_s = tau_s_ * excess,
               .dt_s = duration_s};
}

void AxisPlant::step_for(double command_mm_s, double disturbance_mm_s, double duration_s) noexcept {
  if (duration_s <= 0.0) return;
  advance_with(state_, command_mm_s, disturbance_mm_s, decay_for(duration_s));
}

// Crossing time from 0 = w + (v0 - w) e^{-t*/tau}:  t* = -tau ln(w / (w - v0)) = -tau ln r.
double AxisPlant::travel_to_zero_crossing_mm(double v0_mm_s, double w_mm_s) const noexcept {
  if (w_mm_s == 0.0) return v0_mm_s * tau_s_;  // v0 e^{-t/tau} underflowed: the whole decay
  // r = 1 + v0 / (w - v0); log1p keeps t* accurate for crossings near t = 0.
  const double crossing_s = -tau_s_ * std::log1p(v0_mm_s / (w_mm_s - v0_mm_s));
  // p(t*) - p0 = w t* + (v0 - w) tau (1 - r), and (v0 - w)(1 - r) = v0 exactly.
  return w_mm_s * std::max(crossing_s, 0.0) + v0_mm_s * tau_s_;
}

// With w = K u + d - f (f constant) held over n sub-steps, the exact
// solution telescopes (sum_{k<n} e^{-kh/tau} (1 - e^{-h/tau}) = 1 - e^{-nh/tau}):
//   Q   = (v0 - w) sum_{k<n} e^{-kh/tau}
//   v_n = v0 - (1 - e^{-h/tau}) Q
//   p_n = p0 + n h w + tau (1 - e^{-h/tau}) Q
// Q is zero at steady state, so nothing cancels when the speed is steady.
bool AxisPlant::advance_held_block(AxisState& s, double command_mm_s, double disturbance_mm_s,
                                   std::size_t count) const noexcept {
  if (count == 0 || count > kMaxBlock) return false;
  const double v0_mm_s = s.speed_mm_s;
  const double drive_mm_s = gain_ * command_mm_s + disturbance_mm_s;
  double friction_mm_s = 0.0;
  if (friction_enabled_) {
    if (v0_mm_s == 0.0) {
      // Karnopp, every sub-step alike: at rest within stiction, it stays at rest.
      if (std::abs(drive_mm_s) > friction_.stiction_mm_s()) return false;
      s.stuck = true;
      return true;
    }
    if (!friction_.coulomb_only_beyond(v0_mm_s)) return false;
    friction_mm_s = std::copysign(friction_.coulomb_mm_s(), v0_mm_s);
  }
  const double w_mm_s = drive_mm_s - friction_mm_s;
  // Under an acceleration limit, the closed form holds while |w - v| <= A tau
  // throughout; v runs from v0 toward w, so |w - v0| bounds it.
  if (accel_limited_ && std::abs(w_mm_s - v0_mm_s) > accel_limit_mm_s2_ * tau_s_) return false;
  const double q_mm_s = (v0_mm_s - w_mm_s) * decay_sums_[count];
  const double v_n_mm_s = v0_mm_s - substep_.rise * q_mm_s;
  // v is monotonic from v0 to v_n: both beyond the cutoff on v0's side? (The
  // cutoff's margin covers the rounding between this v_n and the stepped one.)
  if (friction_enabled_ && ((v_n_mm_s > 0.0) != (v0_mm_s > 0.0) || !friction_.coulomb_only_beyond(v_n_mm_s))) {
    return false;
  }
  s.position_mm += kSubstep_s * static_cast<double>(count) * w_mm_s + substep_.tau_rise_s * q_mm_s;
  s.speed_mm_s = v_n_mm_s;
  return true;
}

// The closed form is tried where it can newly hold: at the start of the
// block, after a stop (the law changes) and on leaving the Stribeck zone.
// Held inputs make v_n the same from any start in the block (to rounding),
// so a block declined outside the zone stays declined until a stop.
void AxisPlant::advance_held(AxisState& s, double command_mm_s, double disturbance_mm_s,
                             std::size_t count) const noexcept {
  if (!friction_enabled_ || accel_limited_) {  // rare: tried at every sub-step
    for (std::size_t left = count; left > 0; --left) {
      if (advance_held_block(s, command_mm_s, disturbance_mm_s, left)) return;
      advance(s, command_mm_s, disturbance_mm_s);
    }
    return;
  }
  // The common case: the Karnopp law as advance() calls it (the same bits),
  // the drive computed once, the state a local that stays in registers.
  const double drive_mm_s = gain_ * command_mm_s + disturbance_mm_s;
  AxisState x = s;
  bool try_closed_form = true;
  for (std::size_t left = count; left > 0; --left) {
    if (try_closed_form) {
      AxisState block = x;
      if (advance_held_block(block, command_mm_s, disturbance_mm_s, left)) {
        s = block;
        return;
      }
    }
    const double v0_mm_s = x.speed_mm_s;
    karnopp(x, drive_mm_s, substep_, LinearLaw{*this});
    try_closed_form = x.speed_mm_s == 0.0 ||
                      (!friction_.coulomb_only_beyond(v0_mm_s) && friction_.coulomb_only_beyond(x.speed_mm_s));
  }
  s = x;
}

// The Karnopp switching with the clamped law between switches.
void AxisPlant::advance_limited(AxisState& s, double drive_mm_s, const Decay& d) const noexcept {
  if (!friction_enabled_) {
    advance_clamped(s, drive_mm_s, d);
    return;
  }
  karnopp(s, drive_mm_s, d, ClampedLaw{*this});
}

// dv/dt = clamp((w - v) / tau, -A, A) from v0: a ramp at A sign(w - v0) for
// t1 = (|w - v0| - A tau) / A (while the demand exceeds the limit), then
// v -> w exponentially from w -+ A tau, where the two laws meet.
void AxisPlant::advance_clamped(AxisState& s, double w_mm_s, const Decay& d) const noexcept {
  const double gap_mm_s = w_mm_s - s.speed_mm_s;
  const double limit_gap_mm_s = accel_limit_mm_s2_ * tau_s_;
  if (std::abs(gap_mm_s) <= limit_gap_mm_s) {
    advance_linear(s, w_mm_s, d);
    return;
  }
  const double accel_mm_s2 = std::copysign(accel_limit_mm_s2_, gap_mm_s);
  const double ramp_s = (std::abs(gap_mm_s) - limit_gap_mm_s) / accel_limit_mm_s2_;
  if (ramp_s >= d.dt_s) {
    s.position_mm += (s.speed_mm_s + 0.5 * accel_mm_s2 * d.dt_s) * d.dt_s;
    s.speed_mm_s += accel_mm_s2 * d.dt_s;
    return;
  }
  s.position_mm += (s.speed_mm_s + 0.5 * accel_mm_s2 * ramp_s) * ramp_s;
  s.speed_mm_s = w_mm_s - std::copysign(limit_gap_mm_s, gap_mm_s);
  advance_linear(s, w_mm_s, decay_for(d.dt_s - ramp_s));
}

double AxisPlant::clamped_travel_to_zero_crossing_mm(double v0_mm_s, double w_mm_s) const noexcept {
  const double gap_mm_s = w_mm_s - v0_mm_s;
  const double limit_gap_mm_s = accel_limit_mm_s2_ * tau_s_;
  if (std::abs(gap_mm_s) <= limit_gap_mm_s) return travel_to_zero_crossing_mm(v0_mm_s, w_mm_s);
  const double ramp_s = (std::abs(gap_mm_s) - limit_gap_mm_s) / accel_limit_mm_s2_;
  const double to_zero_s = std::abs(v0_mm_s) / accel_limit_mm_s2_;
  if (to_zero_s <= ramp_s) return 0.5 * v0_mm_s * to_zero_s;  // zero on the ramp
  const double accel_mm_s2 = std::copysign(accel_limit_mm_s2_, gap_mm_s);
  const double ramp_mm = (v0_mm_s + 0.5 * accel_mm_s2 * ramp_s) * ramp_s;
  return ramp_mm + travel_to_zero_crossing_mm(w_mm_s - std::copysign(limit_gap_mm_s, gap_mm_s), w_mm_s);
}

void AxisPlant::set_state(double position_mm, double speed_mm_s, bool stuck) noexcept {
  state_ = AxisState{.position_mm = position_mm,
                     .speed_mm_s = speed_mm_s,
                     .stuck = stuck && speed_mm_s == 0.0 && friction_enabled_};
}

}  // namespace tnv::emu
