#include "firmware/control/sliding_mode_params.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::fw {

SlidingModeParams paper_rdvsc_params(hal::Axis axis) noexcept {
  SlidingModeParams p;
  // One case per axis and no default: a new axis of TNV_AXES fails the
  // build (-Wswitch) until it has its own values here.
  switch (axis) {
    case hal::Axis::x:  // Table 1/2, X axis
    p.G_position_1_s = 287.0;
    p.G_speed = 1.0;
    p.eta_mm_s = 0.1971;
    p.phi_mm_s = 1.273;
    p.q = 0.9;
    p.g = 0.1498;
    p.gamma = 0.4155;
      break;
    case hal::Axis::y:  // Table 1/2, Y axis
    p.G_position_1_s = 203.0;
    p.G_speed = 1.0;
    p.eta_mm_s = 0.1014;
    p.phi_mm_s = 1.722;
    p.q = 0.98;
    p.g = 0.3104;
    p.gamma = 0.3040;
      break;
    case hal::Axis::z:  // no paper table: the autotune rule (tools/tune/axis_design.hpp) on tau_Z = 9.0 ms
    p.G_position_1_s = 167.0;  // G_p tau = 1.5 (X's and Y's tables: 1.54 and 1.45)
    p.G_speed = 1.0;
    p.eta_mm_s = 0.2343;       // 0.4 mm/s scaled by GB: 0.4 x 0.11409 / 0.19475 (the exact X model's GB)
    p.phi_mm_s = 1.233;        // 10 eta / (q + 1)
    p.q = 0.9;
    p.g = 0.3;
    p.gamma = 0.35;            // 0.5 min(1 - g, q)
      break;
  }
  p.u_max_mm_s = kDacFullScaleSpeed_mm_s;
  return p;
}

SlidingModeParams paper_dvsc_params(hal::Axis axis) noexcept {
  SlidingModeParams p = paper_rdvsc_params(axis);
  p.gamma = 0.0;
  return p;
}

SlidingModeParams paper_sliding_mode_params(hal::Axis axis, ControllerKind kind) noexcept {
  return kind == ControllerKind::dvsc ? paper_dvsc_params(axis) : paper_rdvsc_params(axis);
}

ParamCheck validate(const SlidingModeParams& p, const AxisModel& model) noexcept {
  struct Field {
    const char* name;
    const double* value;
  };
  const Field fields[] = {{"G_position_1_s", &p.G_position_1_s}, {"G_speed", &p.G_speed}, {"eta_mm_s", &p.eta_mm_s},
                          {"phi_mm_s", &p.phi_mm_s},             {"q", &p.q},             {"g", &p.g},
                          {"gamma", &p.gamma},                   {"u_max_mm_s", &p.u_max_mm_s}};
  for (const Field& f : fields)
    if (!std::isfinite(*f.value)) return param_error(f.value, f.name, "must be finite (NaN or inf given)");

  if (!(p.q > 0.0 && p.q < 1.0)) return param_error(&p.q, "q", "must satisfy 0 < q < 1 (reaching law, S1 eq. (4))");
  if (!(p.g > 0.0 && p.g < 1.0)) return param_error(&p.g, "g", "must satisfy 0 < g < 1 (|1 - g| < 1, Theorem 1)");
  if (!(p.eta_mm_s > 0.0)) return param_error(&p.eta_mm_s, "eta_mm_s", "must be > 0");
  if (!(p.phi_mm_s > p.eta_mm_s / (p.q + 1.0)))
    return param_error(&p.phi_mm_s, "phi_mm_s", "must satisfy phi > eta / (q + 1) (Theorem 2)");
  if (!(p.gamma >= 0.0 && p.gamma < 1.0)) return param_error(&p.gamma, "gamma", "must satisfy 0 <= gamma < 1");
  if (p.gamma > 0.0 && !(p.gamma < std::min(1.0 - p.g, p.q)))
    return param_error(&p.gamma, "gamma", "must satisfy gamma < min(1 - g, q) (Theorem 5 / Remark 2)");
  if (!(p.u_max_mm_s > 0.0)) return param_error(&p.u_max_mm_s, "u_max_mm_s", "must be > 0");

  if (!is_finite(model)) return param_error(&model.B(1), "model", "A, B and period must be finite, period > 0");
  const double g0 = p.G_position_1_s;
  const double g1 = p.G_speed;
  const double gb = g0 * model.B(0) + g1 * model.B(1);
  const double gb_scale = std::fabs(g0 * model.B(0)) + std::fabs(g1 * model.B(1));
  if (!(std::fabs(gb) > 1e-9 * gb_scale) || !(gb_scale > 0.0))
    return param_error(&p.G_position_1_s, "G", "GB must be non-zero for the model in use (S1 eq. (6) divides by GB)");

  // Zero of G (zI - A)^{-1} B = [z GB + G adj-terms] / det(zI - A); on the
  // surface G e = 0 the remaining error decays with this pole.
  // G adj(zI - A) B = z GB - (g0 (A22 B1 - A12 B2) + g1 (A11 B2 - A21 B1)) for a general 2x2 A.
  const Eigen::Matrix2d& a = model.A;
  const Eigen::Vector2d& b = model.B;
  const double zero_num = g0 * (a(1, 1) * b(0) - a(0, 1) * b(1)) + g1 * (a(0, 0) * b(1) - a(1, 0) * b(0));
  const double z0 = zero_num / gb;
  if (!(std::fabs(z0) < 1.0))
    return param_error(&p.G_position_1_s, "G",
                       "sliding-surface zero dynamics unstable: zero of G(zI-A)^-1 B outside the unit circle");
  return param_ok();
}

}  // namespace tnv::fw
