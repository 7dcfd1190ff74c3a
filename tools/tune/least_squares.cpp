#include "tools/tune/least_squares.hpp"

namespace tnv::tune {

LeastSquares least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& y) {
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  LeastSquares out;
  out.x = qr.solve(y);
  out.rank = qr.rank();
  out.sse = (a * out.x - y).squaredNorm();
  return out;
}

}  // namespace tnv::tune
