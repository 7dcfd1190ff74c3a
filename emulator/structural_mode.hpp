#pragma once
// Optional lightly damped mode between the table and the tool point
// (reference plant "Optional structural mode"): deflection x_d with
//   x_d'' + 2 zeta w x_d' + w^2 x_d = -a_table,
// integrated exactly over each sub-step with a_table held.
// tool position = table position + x_d. mode_hz == 0: no mode, x_d == 0.

namespace tnv::emu {

struct ModeState {
  double deflection_mm = 0.0;
  double deflection_speed_mm_s = 0.0;
};

class StructuralMode {
 public:
  StructuralMode(double mode_hz, double zeta, double step_s) noexcept;

  bool enabled() const noexcept { return enabled_; }
  void step(double table_accel_mm_s2) noexcept { advance(state_, table_accel_mm_s2); }
  // One step on a state the caller holds (keeps it in registers in a loop).
  void advance(ModeState& s, double table_accel_mm_s2) const noexcept {
    if (!enabled_) return;
    const double x = s.deflection_mm;
    const double xdot = s.deflection_speed_mm_s;
    s.deflection_mm = phi11_ * x + phi12_ * xdot + gamma1_ * table_accel_mm_s2;
    s.deflection_speed_mm_s = phi21_ * x + phi22_ * xdot + gamma2_ * table_accel_mm_s2;
  }

  // x_d'' now for a table acceleration a: -a - 2 zeta w x_d' - w^2 x_d
  // (0 without a mode). The tool point accelerates at a + x_d''.
  double deflection_accel_mm_s2(double table_accel_mm_s2) const noexcept {
    if (!enabled_) return 0.0;
    return -table_accel_mm_s2 - two_zeta_w_ * state_.deflection_speed_mm_s - w2_ * state_.deflection_mm;
  }

  double deflection_mm() const noexcept { return state_.deflection_mm; }
  double deflection_speed_mm_s() const noexcept { return state_.deflection_speed_mm_s; }
  const ModeState& state() const noexcept { return state_; }
  void set_state(double deflection_mm, double deflection_speed_mm_s) noexcept {
    state_ = ModeState{deflection_mm, deflection_speed_mm_s};
  }
  void set_state(const ModeState& state) noexcept { state_ = state; }

 private:
  bool enabled_;
  // Zero-order-hold transition matrix and input vector for one step.
  double phi11_ = 1.0, phi12_ = 0.0, phi21_ = 0.0, phi22_ = 1.0;
  double gamma1_ = 0.0, gamma2_ = 0.0;
  double two_zeta_w_ = 0.0, w2_ = 0.0;  // 2 zeta w (1/s), w^2 (1/s^2)
  ModeState state_{};
};

}  // namespace tnv::emu
