#include "firmware/control/speed_observer_design.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::fw {

ObserverDesign steady_state_kalman_gain(const AxisModel& model, const ObserverNoise& noise) noexcept {
  ObserverDesign d;
  if (!is_finite(model) || !std::isfinite(noise.speed_mm_s) || !std::isfinite(noise.disturbance_mm_s) ||
      !std::isfinite(noise.count_mm) || noise.count_mm <= 0.0 || noise.speed_mm_s < 0.0 || noise.disturbance_mm_s < 0.0)
    return d;
  const Eigen::Matrix3d phi = observer_phi(model);
  Eigen::Matrix3d q = Eigen::Matrix3d::Zero();
  q(1, 1) = noise.speed_mm_s * noise.speed_mm_s;
  q(2, 2) = noise.disturbance_mm_s * noise.disturbance_mm_s;
  const double r = noise.count_mm * noise.count_mm / 12.0;  // uniform rounding error of one count
  Eigen::Matrix3d p = Eigen::Matrix3d::Identity() * r;
  Eigen::Vector3d gain = Eigen::Vector3d::Zero();
  constexpr int kMaxIterations = 200000;
  for (int k = 0; k < kMaxIterations; ++k) {
    const double s = p(0, 0) + r;                      // C P C^T + R
    gain = p.col(0) / s;                               // L = P C^T / s
    const Eigen::Matrix3d posterior = p - gain * p.row(0);  // (I - L C) P
    Eigen::Matrix3d next = phi * posterior * phi.transpose() + q;
    next = 0.5 * (next + next.transpose());
    const double change = (next - p).cwiseAbs().maxCoeff();
    p = next;
    d.iterations = k + 1;
    if (change <= 1e-12 * std::max(1.0, p.cwiseAbs().maxCoeff())) break;
  }
  const double s = p(0, 0) + r;
  gain = p.col(0) / s;
  d.innovation_variance_mm2 = s;
  d.params.gain_position = gain(0);
  d.params.gain_speed_1_s = gain(1);
  d.params.gain_disturbance_1_s = gain(2);
  d.ok = gain.allFinite() && observer_error_polynomial(d.params, model).stable;
  return d;
}

}  // namespace tnv::fw
