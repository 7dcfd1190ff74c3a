#include "firmware/control/loop_analysis.hpp"

#include <algorithm>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <numbers>

#include "firmware/control/matrix_poles.hpp"

namespace tnv::fw {

namespace {
using cplx = std::complex<double>;

constexpr double kOmegaLow_rad_s = 0.1;
constexpr int kGridPoints = 4000;
constexpr int kBisections = 80;

double phase_margin_deg(cplx l) noexcept {
  double pm = 180.0 + std::arg(l) * 180.0 / std::numbers::pi;
  if (pm > 180.0) pm -= 360.0;
  return pm;
}

double db(double ratio) noexcept { return 20.0 * std::log10(ratio); }
}  // namespace

std::complex<double> loop_gain(const AxisModel& model, const LinearController& c, double omega_rad_s) noexcept {
  const cplx z = std::polar(1.0, omega_rad_s * model.period_s);
  const Eigen::Vector2cd p =
      (z * Eigen::Matrix2cd::Identity() - model.A.cast<cplx>()).inverse() * model.B.cast<cplx>();
  const Eigen::RowVector2cd k =
      c.Cc.cast<cplx>() * (z * Eigen::Matrix3cd::Identity() - c.Ac.cast<cplx>()).inverse() * c.Bc.cast<cplx>() +
      c.Dc.cast<cplx>();
  return -(k * p).value();
}

LoopMargins loop_margins(const AxisModel& model, const LinearController& c) noexcept {
  LoopMargins m;
  const double inf = std::numeric_limits<double>::infinity();
  m.gain_margin_db = inf;
  m.gain_reduction_margin_db = inf;
  m.phase_margin_deg = inf;
  const double w_nyquist = std::numbers::pi / model.period_s;
  const double log_lo = std::log(kOmegaLow_rad_s);
  const double log_hi = std::log(w_nyquist);
  auto omega_at = [&](int i) { return std::exp(log_lo + (log_hi - log_lo) * i / kGridPoints); };
  // The last grid point stays a hair below Nyquist (where L is real and the
  // sign of Im L is rounding noise); Nyquist itself is checked separately.
  auto grid = [&](int i) { return i == kGridPoints ? w_nyquist * (1.0 - 1e-9) : omega_at(i); };

  auto record_phase_crossing = [&](double w, cplx l) {
    const double mag = std::abs(l);
    if (mag < 1.0) {
      if (-db(mag) < m.gain_margin_db) {
        m.gain_margin_db = -db(mag);
        m.phase_crossover_rad_s = w;
      }
    } else if (db(mag) < m.gain_reduction_margin_db) {
      m.gain_reduction_margin_db = db(mag);
    }
  };

  double w0 = grid(0);
  cplx l0 = loop_gain(model, c, w0);
  for (int i = 1; i <= kGridPoints; ++i) {
    const double w1 = grid(i);
    const cplx l1 = loop_gain(model, c, w1);
    // gain crossover: |L| - 1 changes sign
    if ((std::abs(l0) - 1.0) * (std::abs(l1) - 1.0) < 0.0) {
      double a = w0, b = w1;
      const bool rising = std::abs(l0) < 1.0;
      for (int it = 0; it < kBisections; ++it) {
        const double mid = std::sqrt(a * b);
        const bool below = std::abs(loop_gain(model, c, mid)) < 1.0;
        (below == rising ? a : b) = mid;
      }
      const double wc = std::sqrt(a * b);
      const double pm = phase_margin_deg(loop_gain(model, c, wc));
      ++m.crossover_count;
      m.crossover_found = true;
      m.crossover_rad_s = wc;  // grid is ascending: the last one is the highest
      if (pm < m.phase_margin_deg) m.phase_margin_deg = pm;
    }
    // phase crossover: Im L changes sign on the negative real axis
    if (l0.imag() * l1.imag() < 0.0 && (l0.real() < 0.0 || l1.real() < 0.0)) {
      double a = w0, b = w1;
      const bool im0_negative = l0.imag() < 0.0;
      for (int it = 0; it < kBisections; ++it) {
        const double mid = std::sqrt(a * b);
        const bool negative = loop_gain(model, c, mid).imag() < 0.0;
        (negative == im0_negative ? a : b) = mid;
      }
      const double wp = std::sqrt(a * b);
      const cplx lp = loop_gain(model, c, wp);
      if (lp.real() < 0.0) record_phase_crossing(wp, lp);
    }
    w0 = w1;
    l0 = l1;
  }
  // Nyquist: z = -1, L is real.
  const cplx ln = loop_gain(model, c, w_nyquist);
  if (ln.real() < 0.0) record_phase_crossing(w_nyquist, cplx(ln.real(), 0.0));
  if (!m.crossover_found) m.phase_margin_deg = 0.0;
  return m;
}

ClosedLoopPoles closed_loop_poles(const AxisModel& model, const LinearController& c) noexcept {
  Eigen::Matrix<double, 5, 5> acl;
  acl.topLeftCorner<2, 2>() = model.A + model.B * c.Dc;
  acl.topRightCorner<2, 3>() = model.B * c.Cc;
  acl.bottomLeftCorner<3, 2>() = c.Bc;
  acl.bottomRightCorner<3, 3>() = c.Ac;
  return matrix_poles<5>(acl);
}

double spectral_radius(const ClosedLoopPoles& poles) noexcept {
  double r = 0.0;
  for (const auto& p : poles) {
    const double m = std::abs(p);
    if (!std::isfinite(m)) return std::numeric_limits<double>::infinity();
    r = std::max(r, m);
  }
  return r;
}

}  // namespace tnv::fw
