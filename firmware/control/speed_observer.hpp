#pragma once
// Speed (and position) observer on the identified axis model (issue 7):
// a steady-state Kalman filter in "current estimator" form on the
// disturbance-augmented model, so the loop feeds back a speed estimate
// instead of the M-method's one count per ms (0.42 mm/s of quantisation
// on the reference table).
//
// Model (S1 eq. (3) with d_k held constant between ticks, the identified
// Coulomb friction taken out of it):
//   z = [p, v, d]^T (mm, mm/s, mm/s),  y_k = p_k + quantisation,
//   z_{k+1} = Phi z_k + Gam (u_k - f_k),
//   Phi = [1 A12 B1; 0 A22 B2; 0 0 1],   Gam = [B1; B2; 0]
//   f_k = f_c/K sgn_eps(v^_k)  (friction_mm_s; sgn_eps = 0 inside
//         +-friction_deadband_mm_s, so a resting estimate is not pushed)
// u_k is the command actually applied over the tick (the DAC-quantised
// code read back, 0 while the servo is off). d is what is left: the
// friction's error, stiction, cutting. Without the friction term (f_c = 0)
// d has to follow the 2 f_c step of every reversal and the speed estimate
// lags it; with it, d only follows the model's error.
//
// Per tick (predict with the last applied command, correct with the count):
//   z^-_k = Phi z^_{k-1} + Gam (u_{k-1} - f_{k-1})
//   z^_k  = z^-_k + L (y_k - p^-_k)
// The gain L = [l_p, l_v, l_d] is computed off-line on the host
// (speed_observer_design.hpp: steady-state Kalman gain from stated process
// and measurement noise) and handed over as parameters. Validation refuses a
// non-finite gain and one whose error dynamics (I - L C) Phi are not stable
// (Jury test on the 3rd-order characteristic polynomial), the field named.
//
// Off by default: the tick then uses the M-method speed and the encoder
// position, bit for bit as before (Table 3 untouched).
#include <Eigen/Core>

#include "firmware/control/axis_model.hpp"
#include "firmware/control/param_check.hpp"

namespace tnv::fw {

struct SpeedObserverParams {
  bool enabled = false;
  bool use_position = false;   // also feed back the estimated position (else the encoder's)
  double gain_position = 0.0;  // l_p: share of the innovation added to p^ (dimensionless)
  double gain_speed_1_s = 0.0;         // l_v: mm/s per mm of innovation
  double gain_disturbance_1_s = 0.0;   // l_d: mm/s per mm of innovation
  double friction_mm_s = 0.0;          // f_c / K in command terms (>= 0); 0 = no friction term
  double friction_deadband_mm_s = 0.02;  // |v^| below this: no friction term (> 0)
  bool operator==(const SpeedObserverParams&) const = default;
};

// Finite gains always, friction_mm_s >= 0, friction_deadband_mm_s > 0;
// when enabled, also the error dynamics (I - L C) Phi of `model` stable
// (all poles inside the unit circle; the linear part, the friction term is
// a known input). The all-zero default gains are no observer (Phi has
// poles at 1): fine while off.
ParamCheck validate(const SpeedObserverParams& params, const AxisModel& model) noexcept;


// Coefficients c2, c1, c0 of det(zI - M) = z^3 + c2 z^2 + c1 z + c0 for
// M = (I - L C) Phi, and whether all its roots lie inside the unit circle.
struct ObserverPolynomial {
  double c2 = 0.0;
  double c1 = 0.0;
  double c0 = 0.0;
  bool stable = false;
};
ObserverPolynomial observer_error_polynomial(const SpeedObserverParams& params, const AxisModel& model) noexcept;

class SpeedObserver {
 public:
  // Takes the model and gains (call only with a validated pair).
  void configure(const AxisModel& model, const SpeedObserverParams& params) noexcept;
  // Start from a measurement: p^ = position, v^ = speed, d^ = 0.
  void reset(double position_mm, double speed_mm_s) noexcept;
  // One tick: predict with the command applied over the last tick, correct
  // with this tick's encoder position.
  void update(double measured_position_mm, double applied_command_mm_s) noexcept;
  // The frame moved (zero()): estimate and measurement shift together.
  void shift(double delta_mm) noexcept { z_(0) += delta_mm; }

  double position_mm() const noexcept { return z_(0); }
  double speed_mm_s() const noexcept { return z_(1); }
  double disturbance_mm_s() const noexcept { return z_(2); }
  // The gains of the last configure().
  const SpeedObserverParams& params() const noexcept { return params_; }

 private:
  Eigen::Matrix3d phi_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d gam_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d gain_ = Eigen::Vector3d::Zero();
  double friction_mm_s_ = 0.0;
  double deadband_mm_s_ = 0.02;
  Eigen::Vector3d z_ = Eigen::Vector3d::Zero();
  SpeedObserverParams params_{};
};

// Phi and Gam of the augmented model above.
Eigen::Matrix3d observer_phi(const AxisModel& model) noexcept;
Eigen::Vector3d observer_gamma(const AxisModel& model) noexcept;

}  // namespace tnv::fw
