#pragma once
// A controller as a linear discrete system from the plant state x_k to the
// command u_k (regulation: x_ref = 0, no disturbance). Used at configuration
// time for loop analysis (loop_analysis.hpp) and PID tuning.
//   xi_{k+1} = Ac xi_k + Bc x_k,   u_k = Cc xi_k + Dc x_k
// Three controller states cover both PID (integral, filtered derivative,
// e_{k-1}) and linearised DVSC+DDC (s_{k-1}, d^_{k-1}, one unused).
#include <Eigen/Core>

#include "firmware/control/axis_model.hpp"
#include "firmware/control/sliding_mode_params.hpp"

namespace tnv::fw {

struct LinearController {
  Eigen::Matrix3d Ac = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 3, 2> Bc = Eigen::Matrix<double, 3, 2>::Zero();
  Eigen::RowVector3d Cc = Eigen::RowVector3d::Zero();
  Eigen::RowVector2d Dc = Eigen::RowVector2d::Zero();
};

// DVSC+DDC / R-DVSC+DDC (S1 eqs. (5)-(7)) inside the boundary layer, where
// sat(s/phi) = s/phi; states [s_{k-1}, d^_{k-1}, unused]. With r = q - eta/phi:
//   s_k  = G x_k + gamma s_{k-1}
//   d^_k = d^_{k-1} + (g/GB)(s_k - r s_{k-1})
//   u_k  = -d^_k + (1/GB)(-G A x_k + (r - gamma) s_k)
// params must have passed validate(params, model).
LinearController linearised_sliding_mode(const AxisModel& model, const SlidingModeParams& params) noexcept;

// The PID of pid_controller.hpp without clamp and feed-forward, e = -x_1;
// states [integral term, filtered error rate D_{k-1}, e_{k-1}].
LinearController linear_pid(const AxisModel& model, double kp, double ki, double kd,
                            double derivative_filter_tf_s) noexcept;

}  // namespace tnv::fw
