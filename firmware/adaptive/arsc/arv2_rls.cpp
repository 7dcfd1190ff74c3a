#include "firmware/adaptive/arsc/arv2_rls.hpp"

#include <cmath>

namespace tnv::fw::arsc {

ParamCheck validate(const Arv2RlsParams& p) noexcept {
  if (!std::isfinite(p.forgetting) || !(p.forgetting > 0.0 && p.forgetting <= 1.0))
    return param_error("forgetting", "must satisfy 0 < lambda <= 1");
  if (!std::isfinite(p.initial_covariance) || !(p.initial_covariance > 0.0))
    return param_error("initial_covariance", "must be > 0 and finite");
  return param_ok();
}

Arv2Rls::Arv2Rls(const Arv2RlsParams& params, const Arv2Model& initial) noexcept : params_(params) {
  reset(initial);
}

void Arv2Rls::reset(const Arv2Model& m) noexcept {
  theta_.col(0) << -m.phi1(0, 0), -m.phi1(0, 1), -m.phi2(0, 0), -m.phi2(0, 1), m.theta0(0);
  theta_.col(1) << -m.phi1(1, 0), -m.phi1(1, 1), -m.phi2(1, 0), -m.phi2(1, 1), m.theta0(1);
  p_ = Matrix5::Identity() * params_.initial_covariance;
}

bool Arv2Rls::update(const Vector5& phi, double force, double feed) noexcept {
  const Vector5 p_phi = p_ * phi;
  const double denominator = params_.forgetting + phi.dot(p_phi);
  if (!std::isfinite(denominator) || !(denominator > 0.0)) return false;
  const Vector5 gain = p_phi / denominator;
  const Eigen::RowVector2d error = Eigen::RowVector2d(force, feed) - phi.transpose() * theta_;
  const Eigen::Matrix<double, 5, 2> theta = theta_ + gain * error;
  Matrix5 p = (p_ - gain * p_phi.transpose()) / params_.forgetting;
  p = 0.5 * (p + p.transpose());  // keep P symmetric against round-off
  if (!theta.allFinite() || !p.allFinite()) return false;
  theta_ = theta;
  p_ = p;
  return true;
}

Arv2Model Arv2Rls::model() const noexcept {
  Arv2Model m;
  m.phi1 << -theta_(0, 0), -theta_(1, 0), -theta_(0, 1), -theta_(1, 1);
  m.phi2 << -theta_(2, 0), -theta_(3, 0), -theta_(2, 1), -theta_(3, 1);
  m.theta0 << theta_(4, 0), theta_(4, 1);
  return m;
}

}  // namespace tnv::fw::arsc
