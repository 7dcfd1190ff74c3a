#include "firmware/adaptive/boring/log_model_rls.hpp"

namespace tnv::fw {

void LogModelRls::reset(const BoringTheta& theta0, double p0) noexcept {
  theta_ = theta0;
  reset_covariance(p0);
  innovation_ = 0.0;
}

void LogModelRls::reset_covariance(double p0) noexcept { p_ = p0 * BoringCovariance::Identity(); }

void LogModelRls::restore(const BoringTheta& theta, const BoringCovariance& p, double innovation) noexcept {
  theta_ = theta;
  p_ = p;
  innovation_ = innovation;
}

bool LogModelRls::update(const BoringRegressor& x, double y, double s5, double s6) noexcept {
  if (!(s5 > 0.0) || !(s6 > 0.0) || !std::isfinite(y) || !x.allFinite()) return false;
  const Eigen::Vector3d px = p_ * x;
  const double xpx = x.dot(px);
  const double innovation = y - x.dot(theta_);
  // S4 eq. (5): estimate update.
  const BoringTheta theta = theta_ + px * (innovation / (s5 + xpx));
  // S4 eq. (6): covariance update, kept symmetric against round-off.
  BoringCovariance p = p_ - (px * px.transpose()) / (s6 + xpx);
  p = 0.5 * (p + p.transpose()).eval();
  if (!theta.allFinite() || !p.allFinite()) return false;
  theta_ = theta;
  p_ = p;
  innovation_ = innovation;
  return true;
}

}  // namespace tnv::fw
