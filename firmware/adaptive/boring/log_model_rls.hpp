#pragma once
// Recursive least squares on the log deflection model, S4 eqs. (5), (6):
//   theta_{k+1} = theta_k + P_k x (y - x' theta_k) / (s5 + x' P_k x)   (5)
//   P_{k+1}     = P_k - P_k x x' P_k / (s6 + x' P_k x)                (6)
// The printed paper has s5 = Sigma_k, s6 = 1; the caller chooses
// (BoringGainForm). Fixed size, no allocation; an update whose result is
// not finite changes nothing.
#include "firmware/adaptive/boring/log_model.hpp"

namespace tnv::fw {

class LogModelRls {
 public:
  // theta := theta0, P := p0 I.
  void reset(const BoringTheta& theta0, double p0) noexcept;
  // P := p0 I, theta kept (the variance perturbation).
  void reset_covariance(double p0) noexcept;
  // One measurement (x, y). Returns false, and changes nothing, when s5/s6
  // are not > 0 or the result would not be finite.
  bool update(const BoringRegressor& x, double y, double s5, double s6) noexcept;
  // Puts back a saved estimate exactly (values checked by the caller).
  void restore(const BoringTheta& theta, const BoringCovariance& p, double innovation) noexcept;

  const BoringTheta& theta() const noexcept { return theta_; }
  const BoringCovariance& covariance() const noexcept { return p_; }
  double last_innovation() const noexcept { return innovation_; }  // y - x' theta_k of the last update

 private:
  BoringTheta theta_ = BoringTheta::Zero();
  BoringCovariance p_ = BoringCovariance::Identity();
  double innovation_ = 0.0;
};

}  // namespace tnv::fw
