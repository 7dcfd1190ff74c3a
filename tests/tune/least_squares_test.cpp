// The one least-squares solve (tools/tune/least_squares.hpp): exact data
// gives the coefficients back with zero residual; noisy data its residual;
// collinear columns a rank below the column count.
#include <gtest/gtest.h>

#include <cmath>

#include "tools/tune/least_squares.hpp"

namespace tnv::tune {
namespace {

TEST(LeastSquares, RecoversALineExactlyAndReportsFullRank) {
  Eigen::MatrixXd a(6, 2);
  Eigen::VectorXd y(6);
  for (int i = 0; i < 6; ++i) {
    a(i, 0) = 1.0;
    a(i, 1) = 0.5 * i;
    y(i) = 2.0 - 3.0 * (0.5 * i);
  }
  const LeastSquares ls = least_squares(a, y);
  EXPECT_EQ(ls.rank, 2);
  EXPECT_NEAR(ls.x(0), 2.0, 1e-12);
  EXPECT_NEAR(ls.x(1), -3.0, 1e-12);
  EXPECT_LT(ls.sse, 1e-20);
}

TEST(LeastSquares, ResidualIsWhatTheFitLeaves) {
  // y = 1, 2, 4 on a constant: the mean 7/3 leaves (4/3)^2 + (1/3)^2 + (5/3)^2 = 42/9.
  Eigen::MatrixXd a = Eigen::MatrixXd::Ones(3, 1);
  Eigen::VectorXd y(3);
  y << 1.0, 2.0, 4.0;
  const LeastSquares ls = least_squares(a, y);
  EXPECT_NEAR(ls.x(0), 7.0 / 3.0, 1e-12);
  EXPECT_NEAR(ls.sse, 42.0 / 9.0, 1e-12);
}

TEST(LeastSquares, CollinearColumnsGiveARankBelowTheColumnCount) {
  Eigen::MatrixXd a(4, 2);
  Eigen::VectorXd y(4);
  for (int i = 0; i < 4; ++i) {
    a(i, 0) = i;
    a(i, 1) = 2.0 * i;
    y(i) = i;
  }
  EXPECT_EQ(least_squares(a, y).rank, 1);
}

}  // namespace
}  // namespace tnv::tune
