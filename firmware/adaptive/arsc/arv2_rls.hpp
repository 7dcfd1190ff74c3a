#pragma once
// Recursive least squares for the ARV(2) model, output-decoupled form of
// S3 eq. (5):
//   f(t) = phi(t-1)^T theta1,  v(t) = phi(t-1)^T theta2
//   phi(t-1) = [f(t-1), v(t-1), f(t-2), v(t-2), u(t-1)]
//   theta1 = [-phi111, -phi112, -phi211, -phi212, theta01]
//   theta2 = [-phi121, -phi122, -phi221, -phi222, theta02]
// Both outputs share the regressor, so one covariance P serves both.
// Exponential forgetting lambda (the paper gives none; 1 = plain RLS).
#include <Eigen/Core>

#include "firmware/adaptive/arsc/arv2_model.hpp"
#include "firmware/control/param_check.hpp"

namespace tnv::fw::arsc {

struct Arv2RlsParams {
  double forgetting = 0.98;       // lambda, 0 < lambda <= 1
  double initial_covariance = 1.0;  // P(0) = p0 I, > 0
};

ParamCheck validate(const Arv2RlsParams& params) noexcept;

class Arv2Rls {
 public:
  using Vector5 = Eigen::Matrix<double, 5, 1>;
  using Matrix5 = Eigen::Matrix<double, 5, 5>;

  // params must pass validate().
  Arv2Rls(const Arv2RlsParams& params, const Arv2Model& initial) noexcept;

  void reset(const Arv2Model& initial) noexcept;

  // One update with y(t) = [f(t), v(t)] and phi(t-1). Returns false (and
  // changes nothing) when the update is not finite.
  bool update(const Vector5& regressor, double force, double feed) noexcept;

  Arv2Model model() const noexcept;
  const Matrix5& covariance() const noexcept { return p_; }
  const Eigen::Matrix<double, 5, 2>& theta() const noexcept { return theta_; }

  static Vector5 regressor(double f1, double v1, double f2, double v2, double u1) noexcept {
    Vector5 phi;
    phi << f1, v1, f2, v2, u1;
    return phi;
  }

 private:
  Arv2RlsParams params_;
  Eigen::Matrix<double, 5, 2> theta_;  // columns theta1, theta2
  Matrix5 p_;
};

}  // namespace tnv::fw::arsc
