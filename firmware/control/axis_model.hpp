#pragma once
// The discrete axis model the controllers believe (S1 eq. (3), nominal part):
//   x_{k+1} = A x_k + B u_k,  x = [position mm, velocity mm/s]^T,
//   u = speed command mm/s, sample period T = 1 ms.
#include <Eigen/Core>

#include "hal/axis.hpp"

namespace tnv::fw {

inline constexpr double kControlPeriod_s = 1e-3;

struct AxisModel {
  // Defaults: the paper's X axis (S1 eq. (31)), so AxisModel{} is usable.
  Eigen::Matrix2d A = (Eigen::Matrix2d() << 1.0, 0.0009, 0.0, 0.8298).finished();
  Eigen::Vector2d B = Eigen::Vector2d(0.0001, 0.1702);
  double period_s = kControlPeriod_s;
  bool operator==(const AxisModel&) const = default;
};

// S1 eq. (31): the printed, 4-decimal matrices.
AxisModel paper_axis_model(hal::Axis axis) noexcept;

// Exact zero-order hold of  tau dv/dt = K u - v,  dp/dt = v  over period T:
//   A12 = tau (1 - e^{-T/tau}),  A22 = e^{-T/tau},  B1 = K (T - A12),  B2 = K (1 - A22).
// tau_s > 0 and period_s > 0 are required; otherwise the entries are NaN
// (validation rejects such a model).
AxisModel zoh_axis_model(double tau_s, double gain, double period_s) noexcept;

// All entries finite and period > 0.
bool is_finite(const AxisModel& model) noexcept;

}  // namespace tnv::fw
