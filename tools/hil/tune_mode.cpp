#include "tools/hil/tune_mode.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <numbers>

#include "hal/io_board_registers.hpp"

namespace tnv::hil {

namespace {

struct WindowSolution {
  double sse = 0.0;
  double ring_amplitude = 0.0;  // sqrt(A^2 + B^2); 0 for the table-only model
};

// (G + ridge I) theta = h for n <= 4 columns, by Cholesky; a column whose
// pivot is not positive (collinear with the others) is dropped (theta 0).
// Plain arrays: this runs ~10^4 times per fit, also in sanitizer builds.
void solve_normal_equations(const double (&g)[4][4], const double (&h)[4], int n, double ridge, double (&theta)[4]) {
  double l[4][4] = {};
  double z[4] = {};
  for (int j = 0; j < n; ++j) {
    double d = g[j][j] + ridge;
    for (int k = 0; k < j; ++k) d -= l[j][k] * l[j][k];
    if (!(d > ridge * 1e-6)) continue;  // dropped: l[.][j] stays 0
    l[j][j] = std::sqrt(d);
    for (int i = j + 1; i < n; ++i) {
      double v = g[i][j];
      for (int k = 0; k < j; ++k) v -= l[i][k] * l[j][k];
      l[i][j] = v / l[j][j];
    }
  }
  for (int j = 0; j < n; ++j) {
    if (l[j][j] == 0.0) continue;
    double v = h[j];
    for (int k = 0; k < j; ++k) v -= l[j][k] * z[k];
    z[j] = v / l[j][j];
  }
  for (int j = n - 1; j >= 0; --j) {
    theta[j] = 0.0;
    if (l[j][j] == 0.0) continue;
    double v = z[j];
    for (int k = j + 1; k < n; ++k) v -= l[k][j] * theta[k];
    theta[j] = v / l[j][j];
  }
}

// Least squares of one window on its columns: [e^{-t/tau}] (when tau > 0),
// 1, and with a mode e^{-sigma t} cos(w_d t), e^{-sigma t} sin(w_d t).
// The columns come from recurrences (one complex multiply per sample).
WindowSolution solve_window(const AccelWindow& w, double period_s, bool with_mode, double freq_hz, double zeta,
                            double clip_mm_s2) {
  const bool with_decay = w.table_tau_s > 0.0;
  const int cols = (with_decay ? 1 : 0) + 1 + (with_mode ? 2 : 0);
  double g[4][4] = {};
  double h[4] = {};
  double yy = 0.0;
  const double decay_step = with_decay ? std::exp(-period_s / w.table_tau_s) : 0.0;
  const double omega = 2.0 * std::numbers::pi * freq_hz;
  const std::complex<double> ring_step =
      with_mode ? std::exp(std::complex<double>(-zeta * omega, omega * std::sqrt(1.0 - zeta * zeta)) * period_s)
                : std::complex<double>(0.0, 0.0);
  const double step_re = ring_step.real(), step_im = ring_step.imag();
  double decay = 1.0, ring_re = 1.0, ring_im = 0.0;
  for (const double y : w.accel_mm_s2) {
    // A saturated sample says nothing about the shape: left out.
    if (std::fabs(y) < clip_mm_s2) {
      double phi[4];
      int c = 0;
      if (with_decay) phi[c++] = decay;
      phi[c++] = 1.0;
      if (with_mode) {
        phi[c++] = ring_re;
        phi[c++] = ring_im;
      }
      for (int i = 0; i < cols; ++i) {
        for (int j = 0; j <= i; ++j) g[i][j] += phi[i] * phi[j];
        h[i] += phi[i] * y;
      }
      yy += y * y;
    }
    decay *= decay_step;
    const double re = ring_re * step_re - ring_im * step_im;
    ring_im = ring_re * step_im + ring_im * step_re;
    ring_re = re;
  }
  for (int i = 0; i < cols; ++i)
    for (int j = i + 1; j < cols; ++j) g[i][j] = g[j][i];
  // Tiny ridge: a column that has decayed to nothing (short tau, long window)
  // must not make the system singular.
  double diag_max = 1.0;
  for (int i = 0; i < cols; ++i) diag_max = std::max(diag_max, g[i][i]);
  double theta[4] = {};
  solve_normal_equations(g, h, cols, 1e-12 * diag_max, theta);
  WindowSolution out;
  double explained = 0.0;
  for (int i = 0; i < cols; ++i) explained += h[i] * theta[i];
  out.sse = std::max(0.0, yy - explained);
  if (with_mode) out.ring_amplitude = std::hypot(theta[cols - 2], theta[cols - 1]);
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

nlohmann::json mode_fit_json(const ModeFit& fit) {
  return {{"found", fit.found},
          {"note", fit.note},
          {"freq_hz", fit.freq_hz},
          {"zeta", fit.zeta},
          {"ring_amplitude_mm_s2", fit.ring_amplitude_mm_s2},
          {"explained_share", fit.explained_share},
          {"residual_rms_mm_s2", fit.residual_rms_mm_s2},
          {"samples", fit.samples}};
}

ShaperChoice shaper_for_mode(bool mode_found, double mode_hz, double mode_zeta) {
  ShaperChoice c;
  if (!mode_found) {
    c.note = "no structural mode identified";
    return c;
  }
  c.spec.type = fw::ShaperType::zvd;
  c.spec.mode = {mode_hz, mode_zeta};
  c.spec.second_mode = {0.0, 0.0};
  if (const fw::ParamCheck check = fw::validate(c.spec); !check.ok) {
    c.note = std::string("identified mode outside the shaper's range: ") + check.field + ": " + check.reason;
    return c;
  }
  c.enabled = true;
  return c;
}

nlohmann::json shaper_choice_json(const ShaperChoice& choice) {
  return {{"enable", choice.enabled},
          {"type", choice.enabled ? fw::to_string(choice.spec.type) : "none"},
          {"freq_hz", choice.enabled ? choice.spec.mode.freq_hz : 0.0},
          {"zeta", choice.enabled ? choice.spec.mode.zeta : 0.0},
          {"note", choice.note}};
}

std::string mode_fit_text(const ModeFit& fit, double true_hz, double true_zeta) {
  char line[512];
  if (fit.samples == 0) {
    std::snprintf(line, sizeof line, "  structural mode       not looked for (no accelerometer samples)\n");
  } else if (!fit.found) {
    std::snprintf(line, sizeof line, "  structural mode       none found     %s\n", true_hz > 0.0 ? "scenario has one" : "none");
  } else if (true_hz > 0.0) {
    std::snprintf(line, sizeof line,
                  "  mode f (Hz)           %10.4f    %10.4f       %+6.2f %%\n"
                  "  mode zeta             %10.5f    %10.5f       %+6.2f %%\n",
                  fit.freq_hz, true_hz, 100.0 * (fit.freq_hz / true_hz - 1.0), fit.zeta, true_zeta,
                  true_zeta > 0.0 ? 100.0 * (fit.zeta / true_zeta - 1.0) : 0.0);
  } else {
    std::snprintf(line, sizeof line,
                  "  mode f (Hz)           %10.4f    none\n"
                  "  mode zeta             %10.5f    none\n",
                  fit.freq_hz, fit.zeta);
  }
  std::string text = line;
  std::snprintf(line, sizeof line, "  mode fit: ring %.1f mm/s^2, explains %.1f %% of the table-model residual, rms left %.2f mm/s^2%s%s\n",
                fit.ring_amplitude_mm_s2, 100.0 * fit.explained_share, fit.residual_rms_mm_s2,
                fit.note.empty() ? "" : "; ", fit.note.c_str());
  text += line;
  return text;
}

}  // namespace tnv::hil
