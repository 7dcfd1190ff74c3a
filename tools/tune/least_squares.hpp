#pragma once
// The one small linear least-squares solve of the tuning and fitting code:
// min |A x - y|^2 by column-pivoting Householder QR. Rank-revealing: a rank
// below A's column count says the data cannot determine every coefficient
// (the solution then sets the undetermined ones to zero).
#include <Eigen/Dense>

namespace tnv::tune {

struct LeastSquares {
  Eigen::VectorXd x;
  Eigen::Index rank = 0;
  double sse = 0.0;  // |A x - y|^2 at the solution
};

LeastSquares least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& y);

}  // namespace tnv::tune
