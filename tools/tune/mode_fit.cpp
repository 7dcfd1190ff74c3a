#include "tools/tune/mode_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <numbers>

#include "hal/io_board_registers.hpp"
#include "tools/tune/least_squares.hpp"

namespace tnv::tune {

namespace {

struct WindowSolution {
  double sse = 0.0;
  double ring_amplitude = 0.0;  // sqrt(A^2 + B^2); 0 for the table-only model
};

// Least squares of one window on its columns: [e^{-t/tau}] (when tau > 0),
// 1, and with a mode e^{-sigma t} cos(w_d t), e^{-sigma t} sin(w_d t).
// The columns come from recurrences (one complex multiply per sample). A
// column that has decayed to nothing (short tau, long window) is rank
// deficient: the solve gives it a zero coefficient.
WindowSolution solve_window(const AccelWindow& w, double period_s, bool with_mode, double freq_hz, double zeta,
                            double clip_mm_s2) {
  const bool with_decay = w.table_tau_s > 0.0;
  const int cols = (with_decay ? 1 : 0) + 1 + (with_mode ? 2 : 0);
  Eigen::MatrixXd phi(static_cast<Eigen::Index>(w.accel_mm_s2.size()), cols);
  Eigen::VectorXd y(phi.rows());
  Eigen::Index rows = 0;
  const double decay_step = with_decay ? std::exp(-period_s / w.table_tau_s) : 0.0;
  const double omega = 2.0 * std::numbers::pi * freq_hz;
  const std::complex<double> ring_step =
      with_mode ? std::exp(std::complex<double>(-zeta * omega, omega * std::sqrt(1.0 - zeta * zeta)) * period_s)
                : std::complex<double>(0.0, 0.0);
  const double step_re = ring_step.real(), step_im = ring_step.imag();
  double decay = 1.0, ring_re = 1.0, ring_im = 0.0;
  for (const double sample : w.accel_mm_s2) {
    // A saturated sample says nothing about the shape: left out.
    if (std::fabs(sample) < clip_mm_s2) {
      Eigen::Index c = 0;
      if (with_decay) phi(rows, c++) = decay;
      phi(rows, c++) = 1.0;
      if (with_mode) {
        phi(rows, c++) = ring_re;
        phi(rows, c++) = ring_im;
      }
      y(rows++) = sample;
    }
    decay *= decay_step;
    const double re = ring_re * step_re - ring_im * step_im;
    ring_im = ring_re * step_im + ring_im * step_re;
    ring_re = re;
  }
  WindowSolution out;
  if (rows == 0) return out;
  const LeastSquares ls = least_squares(phi.topRows(rows), y.head(rows));
  out.sse = ls.sse;
  if (with_mode) out.ring_amplitude = std::hypot(ls.x(cols - 2), ls.x(cols - 1));
  return out;
}

struct Candidate {
  double freq_hz = 0.0;
  double zeta = 0.0;
  double sse = std::numeric_limits<double>::infinity();
};

double total_sse(const std::vector<AccelWindow>& windows, double period_s, double freq_hz, double zeta,
                 double clip_mm_s2) {
  double sse = 0.0;
  for (const AccelWindow& w : windows) sse += solve_window(w, period_s, true, freq_hz, zeta, clip_mm_s2).sse;
  return sse;
}

// Best point of the grid f_list x z_list.
Candidate search_grid(const std::vector<AccelWindow>& windows, double period_s, double clip_mm_s2,
                      const std::vector<double>& f_list, const std::vector<double>& z_list) {
  Candidate best;
  for (const double f : f_list)
    for (const double z : z_list) {
      const double sse = total_sse(windows, period_s, f, z, clip_mm_s2);
      if (sse < best.sse) best = {f, z, sse};
    }
  return best;
}

// n points from lo to hi, geometric.
std::vector<double> geometric_points(double lo, double hi, int n) {
  std::vector<double> out;
  for (int i = 0; i < n; ++i) out.push_back(lo * std::pow(hi / lo, static_cast<double>(i) / (n - 1)));
  return out;
}

// The coarse frequency grid's step at f: the SSE's dip in f is about
// 1 / window (5 Hz for 0.2 s) plus zeta f wide, so 2 % of f, at most 1.5 Hz.
double coarse_step_hz(double f_hz) { return std::min(0.02 * f_hz, 1.5); }

}  // namespace

ModeFit fit_mode(const std::vector<AccelWindow>& windows, double period_s, double lsb_mm_s2) {
  ModeFit fit;
  for (const AccelWindow& w : windows) fit.samples += static_cast<int>(w.accel_mm_s2.size());
  if (windows.empty() || fit.samples < 20) {
    fit.note = "too few accelerometer samples";
    return fit;
  }
  // Coarse grid (f in steps of coarse_step_hz, three zetas), then zoom five
  // times around the best point, each time to 1/4 of the span.
  const double clip_mm_s2 = (static_cast<double>(1u << (hal::regs::kAdcBits - 1)) - 1.5) * lsb_mm_s2;  // saturated
  std::vector<double> f_coarse;
  for (double f = kModeSearchMinHz; f <= kModeSearchMaxHz; f += coarse_step_hz(f)) f_coarse.push_back(f);
  constexpr double kCoarseZetaRatio = 6.0;
  const std::vector<double> z_coarse{0.005, 0.005 * kCoarseZetaRatio, 0.005 * kCoarseZetaRatio * kCoarseZetaRatio};
  Candidate best = search_grid(windows, period_s, clip_mm_s2, f_coarse, z_coarse);
  double f_half_span = 2.0 * coarse_step_hz(best.freq_hz);
  double z_ratio = kCoarseZetaRatio;
  constexpr int kZoomPoints = 11, kZooms = 5;
  for (int k = 0; k < kZooms; ++k) {
    const double f_lo = std::max(kModeSearchMinHz, best.freq_hz - f_half_span);
    const double f_hi = std::min(kModeSearchMaxHz, best.freq_hz + f_half_span);
    const double z_lo = std::max(kModeSearchMinZeta, best.zeta / z_ratio);
    const double z_hi = std::min(kModeSearchMaxZeta, best.zeta * z_ratio);
    std::vector<double> f_list;
    for (int i = 0; i < kZoomPoints; ++i) f_list.push_back(f_lo + (f_hi - f_lo) * i / (kZoomPoints - 1));
    const Candidate c = search_grid(windows, period_s, clip_mm_s2, f_list, geometric_points(z_lo, z_hi, kZoomPoints));
    if (c.sse < best.sse) best = c;
    f_half_span *= 0.25;
    z_ratio = std::pow(z_ratio, 0.25);
  }
  double sse_table_only = 0.0;
  for (const AccelWindow& w : windows) {
    sse_table_only += solve_window(w, period_s, false, 0.0, 0.0, clip_mm_s2).sse;
    fit.ring_amplitude_mm_s2 = std::max(fit.ring_amplitude_mm_s2,
                                        solve_window(w, period_s, true, best.freq_hz, best.zeta, clip_mm_s2).ring_amplitude);
  }
  fit.freq_hz = best.freq_hz;
  fit.zeta = best.zeta;
  fit.residual_rms_mm_s2 = std::sqrt(best.sse / fit.samples);
  fit.explained_share = sse_table_only > 0.0 ? 1.0 - best.sse / sse_table_only : 0.0;
  const bool on_edge = best.freq_hz <= kModeSearchMinHz * 1.02 || best.freq_hz >= kModeSearchMaxHz / 1.02 ||
                       best.zeta >= kModeSearchMaxZeta / 1.02;
  char note[200];
  if (fit.explained_share < kMinExplainedShare) {
    std::snprintf(note, sizeof note, "no mode: a damped sinusoid explains %.1f %% of what the table model leaves (< %.0f %%)",
                  fit.explained_share * 100.0, kMinExplainedShare * 100.0);
    fit.note = note;
  } else if (fit.ring_amplitude_mm_s2 < kMinRingLsb * lsb_mm_s2) {
    std::snprintf(note, sizeof note, "no mode: ring amplitude %.1f mm/s^2 is below %.0f LSB", fit.ring_amplitude_mm_s2,
                  kMinRingLsb);
    fit.note = note;
  } else if (on_edge) {
    fit.note = "no mode: the best fit is on the edge of the searched band";
  } else {
    fit.found = true;
  }
  return fit;
}

std::vector<AccelWindow> step_accel_windows(const std::vector<double>& accel_mm_s2, std::size_t drive_ticks,
                                            double tau_s, double speed_mm_s, double coulomb_mm_s, double period_s) {
  std::vector<AccelWindow> out;
  if (accel_mm_s2.size() < 3 || drive_ticks < 2) return out;
  const std::size_t drive_end = std::min(drive_ticks, accel_mm_s2.size() - 1);
  AccelWindow start;
  start.table_tau_s = tau_s;
  start.accel_mm_s2.assign(accel_mm_s2.begin() + 1, accel_mm_s2.begin() + static_cast<std::ptrdiff_t>(drive_end + 1));
  out.push_back(std::move(start));
  // After the drive the table decelerates to rest; with Coulomb friction it
  // stops (and its acceleration drops to 0) at t = tau ln((|V| + f_c) / f_c).
  double stop_s = 0.0;
  if (coulomb_mm_s > 0.0) stop_s = tau_s * std::log((std::fabs(speed_mm_s) + coulomb_mm_s) / coulomb_mm_s);
  const auto stop_ticks = static_cast<std::size_t>(std::ceil(stop_s / period_s)) + 1;
  const std::size_t first = drive_end + stop_ticks;
  if (first + 10 < accel_mm_s2.size()) {
    AccelWindow end;
    end.table_tau_s = tau_s;
    end.accel_mm_s2.assign(accel_mm_s2.begin() + static_cast<std::ptrdiff_t>(first), accel_mm_s2.end());
    out.push_back(std::move(end));
  }
  return out;
}

}  // namespace tnv::tune
