#include "tools/tune/axis_identification.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "hal/io_board_registers.hpp"
#include "tools/tune/least_squares.hpp"

namespace tnv::tune {

namespace {

struct LinearFit {
  double p0 = 0.0;
  double v = 0.0;
  double sse = std::numeric_limits<double>::infinity();
};

// For a fixed tau: p_j = p0 + V g_j, g_j = t - tau (1 - e^{-t/tau}); linear least squares in (p0, V).
LinearFit fit_for_tau(const std::vector<double>& p, double period_s, double tau_s) {
  const auto n = static_cast<Eigen::Index>(p.size());
  Eigen::MatrixXd phi(n, 2);
  Eigen::VectorXd y(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const double t = static_cast<double>(j) * period_s;
    phi(j, 0) = 1.0;
    phi(j, 1) = t - tau_s * (1.0 - std::exp(-t / tau_s));
    y(j) = p[static_cast<std::size_t>(j)] - p[0];
  }
  const LeastSquares ls = least_squares(phi, y);
  LinearFit f;
  f.p0 = ls.x(0) + p[0];
  f.v = ls.x(1);
  f.sse = ls.sse;
  return f;
}

}  // namespace

StepFit fit_step(const std::vector<double>& position_mm, double period_s) {
  StepFit out;
  if (position_mm.size() < 5) return out;
  // Coarse: log grid 0.2 ms .. 200 ms; then golden section around the best.
  constexpr int kGrid = 120;
  const double lo = std::log(2e-4);
  const double hi = std::log(0.2);
  int best = 0;
  double best_sse = std::numeric_limits<double>::infinity();
  for (int i = 0; i < kGrid; ++i) {
    const double tau = std::exp(lo + (hi - lo) * i / (kGrid - 1));
    const double sse = fit_for_tau(position_mm, period_s, tau).sse;
    if (sse < best_sse) {
      best_sse = sse;
      best = i;
    }
  }
  double a = std::exp(lo + (hi - lo) * std::max(0, best - 1) / (kGrid - 1));
  double b = std::exp(lo + (hi - lo) * std::min(kGrid - 1, best + 1) / (kGrid - 1));
  const double r = (std::sqrt(5.0) - 1.0) / 2.0;
  double c = b - r * (b - a);
  double d = a + r * (b - a);
  double fc = fit_for_tau(position_mm, period_s, c).sse;
  double fd = fit_for_tau(position_mm, period_s, d).sse;
  for (int it = 0; it < 80; ++it) {
    if (fc < fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - r * (b - a);
      fc = fit_for_tau(position_mm, period_s, c).sse;
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + r * (b - a);
      fd = fit_for_tau(position_mm, period_s, d).sse;
    }
  }
  out.tau_s = 0.5 * (a + b);
  const LinearFit f = fit_for_tau(position_mm, period_s, out.tau_s);
  out.speed_mm_s = f.v;
  out.rms_residual_mm = std::sqrt(f.sse / static_cast<double>(position_mm.size()));
  return out;
}

namespace {
// The mode from the accelerometer windows of every step (mode_fit.hpp).
void identify_mode(AxisIdentification& id, double period_s) {
  std::vector<AccelWindow> windows;
  for (std::size_t i = 0; i < id.step_records.size() && i < id.steps.size(); ++i) {
    const StepRecord& s = id.step_records[i];
    if (s.accel_mm_s2.empty() || s.position_mm.size() < 2) continue;
    for (AccelWindow& w : step_accel_windows(s.accel_mm_s2, s.position_mm.size() - 1, id.tau_s,
                                             id.steps[i].speed_mm_s, id.coulomb_mm_s, period_s))
      windows.push_back(std::move(w));
  }
  if (windows.empty()) return;
  id.mode_fit = fit_mode(windows, period_s, hal::regs::kAccelFullScaleMmS2 / (1u << (hal::regs::kAdcBits - 1)));
  id.mode_found = id.mode_fit.found;
  id.mode_hz = id.mode_found ? id.mode_fit.freq_hz : 0.0;
  id.mode_zeta = id.mode_found ? id.mode_fit.zeta : 0.0;
}
}  // namespace

AxisIdentification identify_from_records(hal::Axis axis, const std::vector<StepRecord>& steps,
                                         const std::vector<RampRecord>& ramps, double period_s) {
  AxisIdentification id;
  id.axis = axis;
  id.step_records = steps;
  id.ramps = ramps;
  if (steps.size() < 2) {
    id.error = "needs at least two steps";
    return id;
  }
  // tau: the mean of the step fits; K, f_c: V_i = K U_i - sign(U_i) f_c.
  const auto n = static_cast<Eigen::Index>(steps.size());
  Eigen::MatrixXd phi(n, 2);
  Eigen::VectorXd v(n);
  double tau_sum = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const StepRecord& s = steps[static_cast<std::size_t>(i)];
    const StepFit f = fit_step(s.position_mm, period_s);
    if (!(f.tau_s > 0.0)) {
      id.error = "a step record is too short to fit";
      return id;
    }
    id.steps.push_back(f);
    tau_sum += f.tau_s;
    phi(i, 0) = s.level_mm_s;
    phi(i, 1) = s.level_mm_s > 0.0 ? -1.0 : 1.0;
    v(i) = f.speed_mm_s;
  }
  const Eigen::VectorXd theta = least_squares(phi, v).x;
  id.tau_s = tau_sum / static_cast<double>(n);
  id.gain = theta(0);
  id.coulomb_mm_s = std::max(0.0, theta(1));
  double breakaway_sum = 0.0;
  int broke = 0;
  for (const RampRecord& r : ramps) {
    if (!r.broke_away) continue;
    breakaway_sum += std::fabs(r.breakaway_mm_s);
    ++broke;
  }
  if (broke == 0) {
    id.error = "no ramp broke the axis away";
    return id;
  }
  if (!(id.gain > 0.0)) {
    id.error = "fitted gain is not positive";
    return id;
  }
  // The axis breaks away when K |u| > f_s.
  id.stiction_mm_s = std::max(id.coulomb_mm_s, id.gain * breakaway_sum / broke);
  id.model = fw::zoh_axis_model(id.tau_s, id.gain, period_s);
  identify_mode(id, period_s);
  id.ok = fw::is_finite(id.model);
  if (!id.ok) id.error = "the identified model is not finite";
  return id;
}

fw::FrictionFeedForward friction_feedforward_from(const AxisIdentification& id) {
  fw::FrictionFeedForward ff;
  ff.enabled = true;
  ff.coulomb_mm_s = id.coulomb_mm_s;
  // Coulomb only: the Stribeck branch is unstable open loop (slope of f
  // down to -12 mm/s per mm/s on the reference plant, a pole at tau/12,
  // 0.45 ms: faster than the 1 ms tick), so feeding f_s forward makes the
  // axis jump at every reversal; the breakaway excess f_s - f_c is left to
  // the disturbance compensation (S1 eq. 7). Measured: docs/autotune.md.
  ff.stiction_mm_s = id.coulomb_mm_s;
  ff.stribeck_mm_s = kAssumedStribeck_mm_s;
  ff.gain = id.gain;
  ff.fraction = 1.0;
  return ff;
}

}  // namespace tnv::tune
