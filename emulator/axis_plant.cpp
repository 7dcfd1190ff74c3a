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
      substep_(decay_for(kSubstep_s)) {}

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
               .drive_gain_s = tau_s_ * excess};
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

void AxisPlant::set_state(double position_mm, double speed_mm_s, bool stuck) noexcept {
  state_ = AxisState{.position_mm = position_mm,
                     .speed_mm_s = speed_mm_s,
                     .stuck = stuck && speed_mm_s == 0.0 && friction_enabled_};
}

}  // namespace tnv::emu
