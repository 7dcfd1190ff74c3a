#include "firmware/adaptive/arsc/outer_gain_solve.hpp"

#include <Eigen/QR>
#include <cmath>

#include "firmware/adaptive/arsc/polynomial.hpp"

namespace tnv::fw::arsc {

namespace {

using Vector4 = Eigen::Vector4d;
using Matrix4 = Eigen::Matrix4d;

void open_loop(const SampledFeedForce& p, double period_s, Matrix4& a, Vector4& b) noexcept {
  a.setZero();
  a.block<2, 2>(0, 0) = p.phi;
  a.block<2, 1>(0, 2) = p.gamma1;
  a(3, 0) = period_s;  // eta(t+1) = eta(t) + T f(t) - T f*(t)
  a(3, 3) = 1.0;
  b << p.gamma0(0), p.gamma0(1), 1.0, 0.0;  // u(t-1) at t+1 is u(t)
}

// [1, a1, a2, a3, a4] of det(lambda I - a), Faddeev-LeVerrier.
std::array<double, 5> char_poly(const Matrix4& a) noexcept {
  std::array<double, 5> c{};
  c[0] = 1.0;
  Matrix4 m = Matrix4::Zero();
  for (int k = 1; k <= 4; ++k) {
    m = a * m + c[static_cast<std::size_t>(k - 1)] * Matrix4::Identity();
    c[static_cast<std::size_t>(k)] = -(a * m).trace() / static_cast<double>(k);
  }
  return c;
}

bool finite(const SampledFeedForce& p) noexcept {
  return p.phi.allFinite() && p.gamma0.allFinite() && p.gamma1.allFinite();
}

}  // namespace

ParamCheck validate(const OuterPoles& poles) noexcept {
  for (const auto& s : poles.force_s)
    if (!(std::isfinite(s.real()) && std::isfinite(s.imag()))) return param_error("force_s", "must be finite");
  for (const auto& s : poles.force_s)
    if (!(s.real() < 0.0)) return param_error("force_s", "must have Re < 0 (a stable force loop)");
  const bool both_real = poles.force_s[0].imag() == 0.0 && poles.force_s[1].imag() == 0.0;
  if (!both_real && poles.force_s[1] != std::conj(poles.force_s[0]))
    return param_error("force_s", "must be two real poles or a conjugate pair");
  return param_ok();
}

ParamCheck validate(const OuterDesignLimits& l) noexcept {
  if (!std::isfinite(l.max_gain) || !(l.max_gain > 0.0)) return param_error("max_gain", "must be > 0");
  if (!std::isfinite(l.rank_tolerance) || !(l.rank_tolerance > 0.0 && l.rank_tolerance < 1.0))
    return param_error("rank_tolerance", "must satisfy 0 < tolerance < 1");
  return param_ok();
}

std::array<std::complex<double>, 4> outer_target_poles(const SampledFeedForce& plant, double period_s,
                                                       const OuterPoles& poles) noexcept {
  return {std::exp(poles.force_s[0] * period_s), std::exp(poles.force_s[1] * period_s),
          std::complex<double>{plant.drive_pole, 0.0}, std::complex<double>{0.0, 0.0}};
}

OuterDesign solve_outer_gains(const SampledFeedForce& plant, double period_s, const OuterPoles& poles,
                              const OuterDesignLimits& limits) noexcept {
  OuterDesign out;
  if (!finite(plant) || !std::isfinite(period_s) || !(period_s > 0.0)) return out;
  Matrix4 a;
  Vector4 b;
  open_loop(plant, period_s, a, b);
  const Matrix4 a_d = (a - Matrix4::Identity()) / period_s;  // delta operator
  const Vector4 b_d = b / period_s;
  const std::array<double, 5> open = char_poly(a_d);

  // Desired: the same poles in delta, delta = (z - 1) / T.
  std::array<std::complex<double>, 4> delta{};
  const auto z = outer_target_poles(plant, period_s, poles);
  for (std::size_t i = 0; i < 4; ++i) delta[i] = (z[i] - 1.0) / period_s;
  const Poly<5> want = poly_from_roots(delta);  // lowest power first

  // det(lambda I - A_d - B_d K) = a(lambda) - K adj(lambda I - A_d) B_d; the
  // coefficient of lambda^(3-i) of K adj(.) B_d is K sum_{j<=i} a_(i-j) A_d^j B_d.
  Matrix4 q;
  Vector4 rhs;
  Vector4 power_b = b_d;  // A_d^j B_d
  std::array<Vector4, 4> powers{};
  for (std::size_t j = 0; j < 4; ++j) {
    powers[j] = power_b;
    power_b = a_d * power_b;
  }
  for (std::size_t i = 0; i < 4; ++i) {
    Vector4 row = Vector4::Zero();
    for (std::size_t j = 0; j <= i; ++j) row += open[i - j] * powers[j];
    q.row(static_cast<Eigen::Index>(i)) = row.transpose();
    rhs(static_cast<Eigen::Index>(i)) = open[i + 1] - want[3 - i];
  }
  // Row and column scaling: the powers of A_d and the gains differ by orders of magnitude.
  Vector4 col_scale;
  for (int r = 0; r < 4; ++r) {
    const double s = q.row(r).cwiseAbs().maxCoeff();
    if (!(s > 0.0) || !std::isfinite(s)) {
      out.reason = GuardReason::ill_conditioned;
      return out;
    }
    q.row(r) /= s;
    rhs(r) /= s;
  }
  for (int c = 0; c < 4; ++c) {
    const double s = q.col(c).cwiseAbs().maxCoeff();
    col_scale(c) = s > 0.0 && std::isfinite(s) ? s : 1.0;
    q.col(c) /= col_scale(c);
  }
  Eigen::CompleteOrthogonalDecomposition<Matrix4> cod;
  cod.setThreshold(limits.rank_tolerance);
  cod.compute(q);
  const auto& r = cod.matrixQTZ();
  const double r0 = std::fabs(r(0, 0));
  double rmin = r0;
  for (Eigen::Index i = 1; i < cod.rank(); ++i) rmin = std::min(rmin, std::fabs(r(i, i)));
  out.rcond = r0 > 0.0 ? rmin / r0 : 0.0;
  if (cod.rank() < 2) {
    out.reason = GuardReason::ill_conditioned;
    return out;
  }
  const Vector4 k = cod.solve(rhs).cwiseQuotient(col_scale);
  // A rank-deficient set is only acceptable if the identity still holds (the
  // dropped mode is already where it is asked to be).
  const Vector4 residual = q * k.cwiseProduct(col_scale) - rhs;
  if (!k.allFinite()) {
    out.reason = GuardReason::gains_not_finite;
    return out;
  }
  if (!(residual.cwiseAbs().maxCoeff() <= 1e-6 * (1.0 + rhs.cwiseAbs().maxCoeff()))) {
    out.reason = GuardReason::ill_conditioned;
    return out;
  }
  if (!(k.cwiseAbs().maxCoeff() <= limits.max_gain)) {
    out.reason = GuardReason::gain_out_of_range;
    return out;
  }
  out.gains = {k(3), k(0), k(1), k(2)};
  out.reason = GuardReason::none;
  return out;
}

Eigen::Matrix4d outer_closed_loop(const SampledFeedForce& plant, double period_s, const OuterGains& g) noexcept {
  Matrix4 a;
  Vector4 b;
  open_loop(plant, period_s, a, b);
  const Eigen::RowVector4d k(g.gamma31, g.gamma32, g.gamma33, g.k);
  return a + b * k;
}

}  // namespace tnv::fw::arsc
