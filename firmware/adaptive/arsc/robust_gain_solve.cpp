#include "firmware/adaptive/arsc/robust_gain_solve.hpp"

#include <Eigen/Core>
#include <cmath>

#include "firmware/adaptive/arsc/polynomial.hpp"
#include "firmware/adaptive/arsc/scaled_solve.hpp"

namespace tnv::fw::arsc {

namespace {

struct LoopPolys {
  Poly<7> c0;                   // closed loop with the six design gains at 0
  std::array<Poly<7>, 6> m;     // d(closed loop)/d(gain), sign included: C = c0 - sum K_j m_j
  Poly<7> dg0;                  // d(closed loop)/dg with the six design gains at 0
  std::array<Poly<7>, 6> dg;    // its change per unit of each design gain: dC/dg = dg0 - sum K_j dg_j
};

// Everything except the six design gains {k, g11, g13, g22, g31, g32}.
LoopPolys loop_polys(const StructuredModel& model, const ArscGains& g) noexcept {
  const DriveModel& d = model.drive;
  const double gc = model.cutting_gain;
  const Poly<4> a = poly_mul(Poly<2>{0.0, 1.0},
                             poly_axpy<3>(poly_mul(Poly<2>{model.a21, 1.0}, Poly<2>{d.a11, 1.0}), gc * d.c11,
                                          Poly<1>{1.0}));
  const Poly<1> b_f{gc * d.b11};
  const Poly<2> b_v{d.b11 * model.a21, d.b11};
  const Poly<3> den = poly_mul(Poly<2>{-g.gamma01, 1.0}, Poly<2>{-g.gamma03, 1.0});
  const Poly<2> zm1{-1.0, 1.0};
  const Poly<2> r1{-g.gamma41 * g.gamma03, g.gamma41};
  const Poly<2> r2{g.gamma41 * g.gamma02 - g.gamma42 * g.gamma01, g.gamma42};
  const Poly<4> zm1_den = poly_mul(zm1, den);
  const Poly<3> zm1_r1 = poly_mul(zm1, r1);
  const Poly<3> zm1_r2 = poly_mul(zm1, r2);

  LoopPolys p;
  const Poly<7> open = poly_mul(a, zm1_den);
  const Poly<7> fixed_f = poly_pad<7>(poly_mul(b_f, Poly<2>{g.gamma21 * r1[0], g.gamma21 * r1[1]}));
  const Poly<7> fixed_v = poly_pad<7>(poly_mul(b_v, Poly<3>{g.gamma12 * zm1_r1[0], g.gamma12 * zm1_r1[1],
                                                             g.gamma12 * zm1_r1[2]}));
  p.c0 = poly_axpy<7>(poly_axpy<7>(open, -1.0, fixed_f), -1.0, fixed_v);
  p.m[0] = poly_pad<7>(poly_mul(b_f, den));      // k
  p.m[1] = poly_pad<7>(poly_mul(b_f, zm1_r1));   // gamma11
  p.m[2] = poly_pad<7>(poly_mul(b_v, zm1_r2));   // gamma13
  p.m[3] = poly_pad<7>(poly_mul(b_f, r2));       // gamma22
  p.m[4] = poly_pad<7>(poly_mul(b_f, zm1_den));  // gamma31
  p.m[5] = poly_pad<7>(poly_mul(b_v, zm1_den));  // gamma32
  // g enters A (through z g c11) and B_f (= g b11): dC/dg = z c11 (z-1) D - b11 N_f.
  p.dg0 = poly_axpy<7>(poly_pad<7>(poly_mul(Poly<2>{0.0, d.c11}, zm1_den)), -d.b11,
                       Poly<2>{g.gamma21 * r1[0], g.gamma21 * r1[1]});
  p.dg[0] = poly_pad<7>(Poly<3>{d.b11 * den[0], d.b11 * den[1], d.b11 * den[2]});
  p.dg[1] = poly_pad<7>(Poly<3>{d.b11 * zm1_r1[0], d.b11 * zm1_r1[1], d.b11 * zm1_r1[2]});
  p.dg[2] = Poly<7>{};
  p.dg[3] = poly_pad<7>(Poly<2>{d.b11 * r2[0], d.b11 * r2[1]});
  p.dg[4] = poly_pad<7>(Poly<4>{d.b11 * zm1_den[0], d.b11 * zm1_den[1], d.b11 * zm1_den[2], d.b11 * zm1_den[3]});
  p.dg[5] = Poly<7>{};
  return p;
}

bool finite_model(const StructuredModel& m) noexcept {
  return std::isfinite(m.drive.a11) && std::isfinite(m.drive.b11) && std::isfinite(m.drive.c11) &&
         std::isfinite(m.a21) && std::isfinite(m.cutting_gain);
}

}  // namespace

ParamCheck validate(const DriveModel& d) noexcept {
  if (!(std::isfinite(d.a11) && std::isfinite(d.b11) && std::isfinite(d.c11)))
    return param_error("drive", "a11, b11, c11 must be finite");
  if (!(std::fabs(d.a11) < 1.0)) return param_error("drive.a11", "must satisfy |a11| < 1 (a stable feed drive)");
  if (!(d.b11 > 0.0)) return param_error("drive.b11", "must be > 0");
  if (!(d.c11 >= 0.0)) return param_error("drive.c11", "must be >= 0 (the cutting force slows the feed)");
  return param_ok();
}

ParamCheck validate(const RobustDesignLimits& l) noexcept {
  if (!std::isfinite(l.min_rcond) || !(l.min_rcond > 0.0 && l.min_rcond < 1.0))
    return param_error("min_rcond", "must satisfy 0 < min_rcond < 1");
  if (!std::isfinite(l.max_gain) || !(l.max_gain > 0.0)) return param_error("max_gain", "must be > 0");
  return param_ok();
}

RobustDesign solve_robust_gains(const StructuredModel& model, const std::array<double, 6>& d_star,
                                const FixedGains& fixed, const RobustDesignLimits& limits) noexcept {
  RobustDesign out;
  if (!finite_model(model)) return out;
  if (!(std::fabs(model.drive.b11) > 0.0) || !(std::fabs(model.cutting_gain) > 0.0)) {
    out.reason = GuardReason::theta0_zero;  // the input does not reach the force
    return out;
  }
  ArscGains g = with_fixed(fixed);
  g.gamma01 = model.drive.a11 + model.a21 - 1.0 - fixed.gamma03 - d_star[0];  // analogue of S3 eq. (25)
  const LoopPolys p = loop_polys(model, g);

  // Rows: coefficients of z^4 .. z^0, i.e. d2* .. d6*.
  Eigen::Matrix<double, 5, 6> q;
  Eigen::Matrix<double, 5, 1> rhs;
  for (int r = 0; r < 5; ++r) {
    const auto power = static_cast<std::size_t>(4 - r);
    for (int c = 0; c < 6; ++c) q(r, c) = p.m[static_cast<std::size_t>(c)][power];
    rhs(r) = p.c0[power] - d_star[static_cast<std::size_t>(r + 1)];
    const double row_scale = q.row(r).cwiseAbs().maxCoeff();
    if (!(row_scale > 0.0) || !std::isfinite(row_scale)) {
      out.reason = GuardReason::ill_conditioned;
      return out;
    }
    q.row(r) /= row_scale;
    rhs(r) /= row_scale;
  }
  // Minimum-norm solution x = Q^T (Q Q^T)^-1 rhs.
  const Eigen::Matrix<double, 5, 5> normal = q * q.transpose();
  Eigen::Matrix<double, 5, 1> w;
  if (!solve_scaled<5>(normal, rhs, limits.min_rcond, w, out.rcond)) {
    out.reason = GuardReason::ill_conditioned;
    return out;
  }
  Eigen::Matrix<double, 6, 1> x = q.transpose() * w;
  if (limits.free_direction == FreeDirection::min_g_sensitivity) {
    // Null direction of q by cofactors (generalised cross product).
    Eigen::Matrix<double, 6, 1> n;
    for (int j = 0; j < 6; ++j) {
      Eigen::Matrix<double, 5, 5> minor;
      for (int c = 0, m = 0; c < 6; ++c)
        if (c != j) minor.col(m++) = q.col(c);
      n(j) = ((j % 2) ? -1.0 : 1.0) * minor.determinant();
    }
    // dC/dg along x + alpha n: s_p - alpha w_g; least squares in alpha.
    Eigen::Matrix<double, 7, 1> s_p, w_g;
    for (std::size_t i = 0; i < 7; ++i) {
      s_p(static_cast<Eigen::Index>(i)) = p.dg0[i];
      w_g(static_cast<Eigen::Index>(i)) = 0.0;
      for (std::size_t j = 0; j < 6; ++j) {
        s_p(static_cast<Eigen::Index>(i)) -= x(static_cast<Eigen::Index>(j)) * p.dg[j][i];
        w_g(static_cast<Eigen::Index>(i)) += n(static_cast<Eigen::Index>(j)) * p.dg[j][i];
      }
    }
    const double ww = w_g.squaredNorm();
    if (ww > 1e-300 && std::isfinite(ww)) x += (s_p.dot(w_g) / ww) * n;
  }
  if (!x.allFinite() || !std::isfinite(g.gamma01)) {
    out.reason = GuardReason::gains_not_finite;
    return out;
  }
  if (!(x.cwiseAbs().maxCoeff() <= limits.max_gain) || !(std::fabs(g.gamma01) <= limits.max_gain)) {
    out.reason = GuardReason::gain_out_of_range;
    return out;
  }
  set_solved_gains(g, x);
  out.gains = g;
  out.reason = GuardReason::none;
  return out;
}

std::array<double, 6> robust_closed_loop_coefficients(const StructuredModel& model, const ArscGains& g) noexcept {
  const LoopPolys p = loop_polys(model, g);
  const double kv[6] = {g.k, g.gamma11, g.gamma13, g.gamma22, g.gamma31, g.gamma32};
  Poly<7> c = p.c0;
  for (std::size_t j = 0; j < 6; ++j)
    for (std::size_t i = 0; i < 7; ++i) c[i] -= kv[j] * p.m[j][i];
  std::array<double, 6> d{};
  for (std::size_t i = 0; i < 6; ++i) d[i] = c[5 - i] / c[6];
  return d;
}

}  // namespace tnv::fw::arsc
