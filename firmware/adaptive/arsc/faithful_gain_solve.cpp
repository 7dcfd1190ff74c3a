#include "firmware/adaptive/arsc/faithful_gain_solve.hpp"

#include <cmath>

#include "firmware/adaptive/arsc/scaled_solve.hpp"

namespace tnv::fw::arsc {

ParamCheck validate(const GuardLimits& g) noexcept {
  if (!std::isfinite(g.min_theta0) || !(g.min_theta0 > 0.0)) return param_error("min_theta0", "must be > 0");
  if (!std::isfinite(g.min_phi1_rank) || !(g.min_phi1_rank > 0.0))
    return param_error("min_phi1_rank", "must be > 0");
  if (!std::isfinite(g.min_rcond) || !(g.min_rcond > 0.0 && g.min_rcond < 1.0))
    return param_error("min_rcond", "must satisfy 0 < min_rcond < 1");
  return param_ok();
}

ParamCheck validate(const FixedGains& f) noexcept {
  const double v[] = {f.gamma02, f.gamma03, f.gamma12, f.gamma21, f.gamma41, f.gamma42};
  for (double x : v)
    if (!std::isfinite(x)) return param_error("fixed", "fixed gains must be finite");
  return param_ok();
}

GuardReason check_model(const Arv2Model& m, const GuardLimits& limits, JuryFailure& jury) noexcept {
  jury = JuryFailure::none;
  if (!is_finite(m)) return GuardReason::model_not_finite;
  if (!(m.theta0.norm() >= limits.min_theta0)) return GuardReason::theta0_zero;  // S3: theta0 != 0
  const double scale = m.phi1.squaredNorm();
  if (!(std::fabs(m.phi1.determinant()) >= limits.min_phi1_rank * scale) || !(scale > 0.0))
    return GuardReason::phi1_rank;  // S3: rank Phi1 = 2
  const JuryResult j = jury_quartic(open_loop_quartic(m));  // S3 eqs. (30)-(31)
  jury = j.failure;
  if (!j.stable) return GuardReason::model_unstable;
  return GuardReason::none;
}

Fig3System fig3_system(const Arv2Model& m, const std::array<double, 7>& ds, const FixedGains& f) noexcept {
  const double p111 = m.phi1(0, 0), p112 = m.phi1(0, 1), p121 = m.phi1(1, 0), p122 = m.phi1(1, 1);
  const double p211 = m.phi2(0, 0), p212 = m.phi2(0, 1), p221 = m.phi2(1, 0), p222 = m.phi2(1, 1);
  const double t1 = m.theta0(0), t2 = m.theta0(1);
  const double g02 = f.gamma02, g03 = f.gamma03, g12 = f.gamma12, g21 = f.gamma21, g41 = f.gamma41,
               g42 = f.gamma42;
  // S3 Fig. 3 auxiliaries
  const double d1a = p111 * t2 - p121 * t1;
  const double d2a = p112 * t2 - p122 * t1;
  const double d3a = p211 * t2 - p221 * t1;
  const double d4a = p212 * t2 - p222 * t1;
  const double d12 = p111 * p122 - p121 * p112;
  const double d23 = p112 * p221 - p122 * p211;
  const double d34 = p211 * p222 - p221 * p212;
  const double d14 = p111 * p222 - p121 * p212;
  const double h4 = p111 + p122 - 1.0 - ds[0];  // corrected: = gamma01 + gamma03
  const double g01 = h4 - g03;                   // S3 eq. (25): gamma01
  const double h1 = g42 * g01 - g41 * g02;
  const double h2 = g41 * g03;
  const double h3 = 1.0 - p111 - p122;
  const double h5 = g01 * g03;
  const double h6 = t2 - d1a;
  const double h7 = d3a - d1a;
  const double h8 = t1 + d2a;
  const double h9 = d2a - d4a;
  const double h10 = d12 - p111 - p122 + p211 + p222;
  const double h11 = d12 + d23 - d14 + p211 + p222;
  const double h12 = d34 + d23 - d14;
  const double h13 = h2 * g12;
  const double h14 = h2 * g21;
  const double h15 = g41 * g12;
  const double h16 = g41 * g21;

  Fig3System s;
  s.gamma01 = g01;
  // S3 Fig. 3(a), columns K^v = [k, gamma11, gamma13, gamma22, gamma31, gamma32]
  s.p << 0.0, 0.0, 0.0, 0.0, -t1, -t2,                                                       // d2
      -t1, -g41 * t1, -g42 * t2, 0.0, h8 + h4 * t1, h6 + h4 * t2,                            // d3
      d2a + h4 * t1, g41 * h8 + h2 * t1, g42 * h6 + h1 * t2, -g42 * t1,                      // d4 (+g42 h6: fix)
      -h9 - h4 * h8 - h5 * t1, -h7 - h4 * h6 - h5 * t2,                                      //
      d4a - h4 * d2a - h5 * t1, -g41 * h9 - h2 * h8, -g42 * h7 - h1 * h6, g42 * d2a + h1 * t1,  // d5
      -d4a + h4 * h9 + h5 * h8, d3a + h4 * h7 + h5 * h6,                                     //
      -h4 * d4a + h5 * d2a, -g41 * d4a + h2 * h9, g42 * d3a + h1 * h7, g42 * d4a - h1 * d2a,  // d6
      h4 * d4a - h5 * h9, -h4 * d3a - h5 * h7,                                               //
      h5 * d4a, h2 * d4a, -h1 * d3a, -h1 * d4a, -h5 * d4a, h5 * d3a;                         // d7
  // S3 Fig. 3(b), D* = {d2*, ..., d7*}
  s.delta << ds[1] - h10 - h4 * h3 - h5,                                                      //
      ds[2] + h15 * t2 + h11 + h4 * h10 + h5 * h3,                                            //
      ds[3] - h15 * h6 - h13 * t2 + h16 * t1 - h12 - h4 * h11 - h5 * h10,                     // (fix)
      ds[4] + h15 * h7 + h13 * h6 - h16 * d2a - h14 * t1 + d34 + h4 * h12 + h5 * h11,         //
      ds[5] - h15 * d3a - h13 * h7 - h16 * d4a + h14 * d2a - h4 * d34 - h5 * h12,             //
      ds[6] + h13 * d3a + h14 * d4a + h5 * d34;
  return s;
}


GainDesign solve_faithful_gains(const Arv2Model& model, const std::array<double, 7>& d_star,
                                const FixedGains& fixed, const GuardLimits& limits) noexcept {
  GainDesign out;
  out.reason = check_model(model, limits, out.jury);
  if (out.reason != GuardReason::none) return out;
  const Fig3System sys = fig3_system(model, d_star, fixed);
  if (!sys.p.allFinite() || !sys.delta.allFinite()) {
    out.reason = GuardReason::ill_conditioned;
    return out;
  }
  Eigen::Matrix<double, 6, 1> kv;
  if (!solve_scaled<6>(sys.p, sys.delta, limits.min_rcond, kv, out.rcond)) {  // S3 eq. (26)
    out.reason = GuardReason::ill_conditioned;
    return out;
  }
  if (!kv.allFinite() || !std::isfinite(sys.gamma01)) {
    out.reason = GuardReason::gains_not_finite;
    return out;
  }
  ArscGains g = with_fixed(fixed);
  g.gamma01 = sys.gamma01;
  set_solved_gains(g, kv);
  out.gains = g;
  out.reason = GuardReason::none;
  return out;
}

}  // namespace tnv::fw::arsc
