#pragma once
// The ARSC gain vector K (S3 eq. (18)) and the split the paper uses for the
// on-line update: seven gains computed from the desired poles, six fixed
// (S3 eq. (32)).
#include <Eigen/Core>

namespace tnv::fw::arsc {

struct ArscGains {
  double k = 0.0;  // servo-compensator gain                   S3 eq. (11)
  double gamma31 = 0.0, gamma32 = 0.0;  // output feedback     S3 eq. (11)
  double gamma41 = 1.0, gamma42 = 1.0;  // compensator feedback S3 eq. (11)
  double gamma01 = 0.0, gamma02 = 0.5, gamma03 = 0.1;  // stabilising compensator  S3 eq. (10)
  double gamma11 = 0.0, gamma12 = 1.0, gamma13 = 0.0;
  double gamma21 = 1.0, gamma22 = 0.0;
};

// The gains the paper fixes before the on-line update (K^r of S3 eq. (26)
// without gamma01), S3 eq. (32).
struct FixedGains {
  double gamma02 = 0.5;
  double gamma03 = 0.1;
  double gamma12 = 1.0;
  double gamma21 = 1.0;
  double gamma41 = 1.0;
  double gamma42 = 1.0;
};

// The six gains the on-line design solves for, in the order of the
// unknown vector of S3 eq. (26): {k, gamma11, gamma13, gamma22, gamma31, gamma32}.
inline void set_solved_gains(ArscGains& g, const Eigen::Matrix<double, 6, 1>& kv) noexcept {
  g.k = kv(0);
  g.gamma11 = kv(1);
  g.gamma13 = kv(2);
  g.gamma22 = kv(3);
  g.gamma31 = kv(4);
  g.gamma32 = kv(5);
}

inline ArscGains with_fixed(const FixedGains& f) noexcept {
  ArscGains g;
  g.gamma02 = f.gamma02;
  g.gamma03 = f.gamma03;
  g.gamma12 = f.gamma12;
  g.gamma21 = f.gamma21;
  g.gamma41 = f.gamma41;
  g.gamma42 = f.gamma42;
  return g;
}

}  // namespace tnv::fw::arsc
