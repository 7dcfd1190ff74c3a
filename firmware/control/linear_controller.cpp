#include "firmware/control/linear_controller.hpp"

namespace tnv::fw {

LinearController linearised_sliding_mode(const AxisModel& model, const SlidingModeParams& p) noexcept {
  const Eigen::RowVector2d G(p.G_position_1_s, p.G_speed);
  const double gb = (G * model.B).value();
  const double r = p.q - p.eta_mm_s / p.phi_mm_s;  // S1 eq. (14): in-layer pole
  const double gamma = p.gamma;
  const double kg = p.g / gb;
  LinearController c;
  // S1 eq. (5): s_k = G x_k + gamma s_{k-1}
  c.Ac(0, 0) = gamma;
  c.Bc.row(0) = G;
  // S1 eq. (7), linearised: d^_k = d^_{k-1} + (g/GB)(G x_k + (gamma - r) s_{k-1})
  c.Ac(1, 0) = kg * (gamma - r);
  c.Ac(1, 1) = 1.0;
  c.Bc.row(1) = kg * G;
  // S1 eq. (6), linearised, with s_k and d^_k substituted
  c.Cc(0) = -kg * (gamma - r) + (r - gamma) * gamma / gb;
  c.Cc(1) = -1.0;
  c.Dc = -kg * G + (1.0 / gb) * (-G * model.A + (r - gamma) * G);
  return c;
}

LinearController linear_pid(const AxisModel& model, double kp, double ki, double kd,
                            double derivative_filter_tf_s) noexcept {
  const double t = model.period_s;
  const double a = derivative_filter_tf_s / (derivative_filter_tf_s + t);
  const double b = (1.0 - a) / t;  // D_k = a D_{k-1} + b (e_k - e_{k-1})
  LinearController c;
  // e_k = -x_1,k (position error with zero reference)
  c.Ac(0, 0) = 1.0;  // I_k = I_{k-1} + ki T e_k
  c.Bc(0, 0) = -ki * t;
  c.Ac(1, 1) = a;
  c.Ac(1, 2) = -b;
  c.Bc(1, 0) = -b;
  c.Bc(2, 0) = -1.0;  // e_{k-1} <- e_k
  // u_k = kp e_k + I_k + kd D_k
  c.Cc << 1.0, kd * a, -kd * b;
  c.Dc << -(kp + ki * t + kd * b), 0.0;
  return c;
}

}  // namespace tnv::fw
