#pragma once
// One table axis: servopack speed loop + ball screw (reference plant "Axis"),
//   dp/dt = v,   tau dv/dt = K u + d_cut - f_fric(v) - v,
// stepped over sub-steps with u, d_cut and the friction force held at their
// start-of-sub-step values, so the linear part is integrated exactly.
// With accel_limit_mm_s2 = A > 0 (the servopack's current limit) the law is
//   dv/dt = clamp((K u + d_cut - f - v) / tau, -A, A),
// also integrated exactly: a ramp at +-A until |w - v| = A tau, then the
// exponential approach (accel_limit below).
// p is the motor side (what the encoder counts); the table is
// ScrewTransmission's (screw_transmission.hpp), the same when it is off.
#include <array>
#include <cmath>
#include <cstddef>

#include "emulator/scenario.hpp"
#include "emulator/stribeck_friction.hpp"

namespace tnv::emu {

struct AxisState {
  double position_mm = 0.0;
  double speed_mm_s = 0.0;
  bool stuck = false;  // Karnopp: held by stiction (speed is then exactly 0)
};

class AxisPlant {
 public:
  static constexpr std::size_t kMaxBlock = 100;  // longest advance_held_block

  explicit AxisPlant(const AxisPlantParams& params) noexcept;

  // One 10 us sub-step (precomputed exponentials; the hot path).
  void step(double command_mm_s, double disturbance_mm_s) noexcept { advance(state_, command_mm_s, disturbance_mm_s); }
  // Same law over any duration (tests, identification tools).
  void step_for(double command_mm_s, double disturbance_mm_s, double duration_s) noexcept;
  // One sub-step on a state the caller holds (lets a block of sub-steps keep
  // the state in registers).
  void advance(AxisState& state, double command_mm_s, double disturbance_mm_s) const noexcept {
    advance_with(state, command_mm_s, disturbance_mm_s, substep_);
  }

  // `count` (<= kMaxBlock) sub-steps with command u and disturbance d held,
  // in one closed form, when that is provably the same as stepping: friction
  // off; or the speed stays beyond the Stribeck cutoff on one side for the
  // whole block, where friction is exactly +-f_c at every sub-step start
  // (v runs monotonically from v0 to v_n, so checking both ends suffices);
  // or the axis rests, stuck, with |K u + d| <= f_s (Karnopp: it stays so).
  // Returns false and leaves `state` alone otherwise.
  bool advance_held_block(AxisState& state, double command_mm_s, double disturbance_mm_s,
                          std::size_t count) const noexcept;
  // `count` (<= kMaxBlock) sub-steps with u and d held: single sub-steps
  // until the rest of the block has the closed form above, then that.
  void advance_held(AxisState& state, double command_mm_s, double disturbance_mm_s, std::size_t count) const noexcept;

  double position_mm() const noexcept { return state_.position_mm; }
  double speed_mm_s() const noexcept { return state_.speed_mm_s; }
  bool stuck() const noexcept { return state_.stuck; }
  const AxisState& state() const noexcept { return state_; }
  bool friction_enabled() const noexcept { return friction_enabled_; }
  double tau_s() const noexcept { return tau_s_; }
  double gain() const noexcept { return gain_; }
  const StribeckFriction& friction() const noexcept { return friction_; }
  // |dv/dt| limit in mm/s^2; 0 = none.
  double accel_limit_mm_s2() const noexcept { return accel_limited_ ? accel_limit_mm_s2_ : 0.0; }

  // Test / identification bench. stuck only holds for speed 0 with friction on;
  // a resting axis (v == 0) gets the Karnopp test at its next step either way.
  void set_state(double position_mm, double speed_mm_s, bool stuck = false) noexcept;
  void set_state(const AxisState& state) noexcept { set_state(state.position_mm, state.speed_mm_s, state.stuck); }

 private:
  // Exact solution over a step dt with w = K u + d - f held (v -> w with time
  // constant tau), written so the speed recursion is one multiply-add:
  //   v(dt) = e^{-dt/tau} v0 + (1 - e^{-dt/tau}) w
  //   p(dt) = p0 + (dt - tau (1 - e^{-dt/tau})) w + tau (1 - e^{-dt/tau}) v0
  struct Decay {
    double decay;         // e^{-dt/tau}
    double rise;          // 1 - decay, exact in floating point (so v -> w exactly)
    double tau_rise_s;    // tau (1 - e^{-dt/tau})
    double drive_gain_s;  // dt - tau (1 - e^{-dt/tau})
    double dt_s;
  };
  Decay decay_for(double duration_s) const noexcept;

  void advance_with(AxisState& s, double command_mm_s, double disturbance_mm_s, const Decay& d) const noexcept;
  static void advance_linear(AxisState& s, double w_mm_s, const Decay& d) noexcept {
    s.position_mm += d.drive_gain_s * w_mm_s + d.tau_rise_s * s.speed_mm_s;
    s.speed_mm_s = d.decay * s.speed_mm_s + d.rise * w_mm_s;
  }
  // Distance travelled from speed v0 until v first reaches zero (v0, w of
  // opposite signs). Out of line and by value, so a caller's state can stay in registers.
  double travel_to_zero_crossing_mm(double v0_mm_s, double w_mm_s) const noexcept;

  // The same sub-step law under the acceleration limit (out of line: off the hot path).
  void advance_limited(AxisState& s, double drive_mm_s, const Decay& d) const noexcept;
  // v -> w with |dv/dt| <= A over d.dt_s, no friction switching.
  void advance_clamped(AxisState& s, double w_mm_s, const Decay& d) const noexcept;
  double clamped_travel_to_zero_crossing_mm(double v0_mm_s, double w_mm_s) const noexcept;

  // Karnopp stick/slip (reference plant), the one switching law of both
  // speed laws: at rest the axis sticks while |K u + d_cut| <= f_s and breaks
  // away against f_s; moving, friction f(v0) opposes it, and a zero crossing
  // of v inside the step puts it into the stuck state for the rest of the
  // step (the next step tests break-away). `Law` moves the axis with a net
  // drive w held over the step: free(s, w, d); slide(s, drive, |f|, w, d),
  // the state after the step were there no switch; travel_to_zero(v0, w).
  template <typename Law>
  void karnopp(AxisState& s, double drive_mm_s, const Decay& d, const Law& law) const noexcept;
  // The linear law (v -> w with time constant tau) and the clamped one.
  struct LinearLaw {
    const AxisPlant& plant;
    void free(AxisState& s, double w_mm_s, const Decay& d) const noexcept { advance_linear(s, w_mm_s, d); }
    AxisState slide(const AxisState& s, double drive_mm_s, double friction_mm_s, double w_mm_s,
                    const Decay& d) const noexcept {
      AxisState next = s;
      // Grouped to keep the v0 -> v1 dependency chain short (this is the hot
      // loop): the sign goes on the rise, known before the friction is, and
      // (+-rise) f is bit for bit +-(rise f).
      next.speed_mm_s =
          (d.decay * s.speed_mm_s + d.rise * drive_mm_s) - std::copysign(d.rise, s.speed_mm_s) * friction_mm_s;
      next.position_mm += d.drive_gain_s * w_mm_s + d.tau_rise_s * s.speed_mm_s;
      return next;
    }
    double travel_to_zero(double v0_mm_s, double w_mm_s) const noexcept {
      return plant.travel_to_zero_crossing_mm(v0_mm_s, w_mm_s);
    }
  };
  struct ClampedLaw {
    const AxisPlant& plant;
    void free(AxisState& s, double w_mm_s, const Decay& d) const noexcept { plant.advance_clamped(s, w_mm_s, d); }
    AxisState slide(const AxisState& s, double, double, double w_mm_s, const Decay& d) const noexcept {
      AxisState next = s;
      plant.advance_clamped(next, w_mm_s, d);
      return next;
    }
    double travel_to_zero(double v0_mm_s, double w_mm_s) const noexcept {
      return plant.clamped_travel_to_zero_crossing_mm(v0_mm_s, w_mm_s);
    }
  };

  double tau_s_;
  double gain_;
  StribeckFriction friction_;
  bool friction_enabled_;
  double accel_limit_mm_s2_;
  bool accel_limited_;
  Decay substep_;
  std::array<double, kMaxBlock + 1> decay_sums_;  // sum_{k<n} e^{-k h/tau}, n = 0..kMaxBlock
  AxisState state_{};
};

inline void AxisPlant::advance_with(AxisState& s, double command_mm_s, double disturbance_mm_s,
                                    const Decay& d) const noexcept {
  const double drive_mm_s = gain_ * command_mm_s + disturbance_mm_s;
  if (accel_limited_) {
    advance_limited(s, drive_mm_s, d);
    return;
  }
  if (!friction_enabled_) {
    advance_linear(s, drive_mm_s, d);
    return;
  }
  karnopp(s, drive_mm_s, d, LinearLaw{*this});
}

template <typename Law>
inline void AxisPlant::karnopp(AxisState& s, double drive_mm_s, const Decay& d, const Law& law) const noexcept {
  const double v0_mm_s = s.speed_mm_s;
  if (v0_mm_s == 0.0) {
    // reference plant: Karnopp stick condition |K u + d_cut| <= f_s
    if (std::abs(drive_mm_s) <= friction_.stiction_mm_s()) {
      s.stuck = true;
      return;
    }
    // Break-away: friction at v = 0+ in the direction of the drive is f_s.
    s.stuck = false;
    law.free(s, drive_mm_s - std::copysign(friction_.stiction_mm_s(), drive_mm_s), d);
    return;
  }
  const double friction_mm_s = friction_.magnitude_mm_s(v0_mm_s);  // |f(v0)|, signed below
  const double w_mm_s = drive_mm_s - std::copysign(friction_mm_s, v0_mm_s);
  const AxisState next = law.slide(s, drive_mm_s, friction_mm_s, w_mm_s, d);
  // v(t) runs monotonically from v0 toward w, so it crosses zero inside the
  // step iff v(dt) is zero or has flipped sign.
  if (next.speed_mm_s == 0.0 || (next.speed_mm_s > 0.0) != (v0_mm_s > 0.0)) {
    // reference plant: "a zero crossing of v inside a sub-step is located
    // exactly and puts the axis into the stuck state" (for the rest of the
    // sub-step; the next step tests break-away).
    s.position_mm += law.travel_to_zero(v0_mm_s, w_mm_s);
    s.speed_mm_s = 0.0;
    s.stuck = true;
    return;
  }
  s = next;
}

}  // namespace tnv::emu
