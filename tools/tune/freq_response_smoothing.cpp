#include "tools/tune/freq_response_smoothing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>

namespace tnv::tune {

namespace {

double coherence_weight(double coherence) {
  const double g = std::clamp(coherence, 1e-9, 1.0 - 1e-9);
  return g / (1.0 - g);
}

// The value at t = 0 of the weighted least-squares polynomial of degree
// <= 2 through (t_i, y_i); the degree falls when the points cannot carry it.
double local_fit_at_zero(const std::vector<double>& t, const std::vector<double>& y, const std::vector<double>& w) {
  for (int degree = std::min<int>(2, static_cast<int>(t.size()) - 1); degree >= 0; --degree) {
    const int n = degree + 1;
    std::array<std::array<double, 4>, 3> m{};  // normal equations, augmented
    for (std::size_t i = 0; i < t.size(); ++i) {
      double pa = 1.0;
      for (int a = 0; a < n; ++a) {
        double pb = 1.0;
        for (int b = 0; b < n; ++b) {
          m[a][b] += w[i] * pa * pb;
          pb *= t[i];
        }
        m[a][n] += w[i] * pa * y[i];
        pa *= t[i];
      }
    }
    bool singular = false;
    for (int c = 0; c < n && !singular; ++c) {  // Gauss-Jordan with partial pivoting
      int pivot = c;
      for (int r = c + 1; r < n; ++r)
        if (std::fabs(m[r][c]) > std::fabs(m[pivot][c])) pivot = r;
      std::swap(m[c], m[pivot]);
      if (!(std::fabs(m[c][c]) > 1e-12 * std::fabs(m[0][0]))) {
        singular = true;
        break;
      }
      for (int r = 0; r < n; ++r) {
        if (r == c) continue;
        const double k = m[r][c] / m[c][c];
        for (int q = c; q <= n; ++q) m[r][q] -= k * m[c][q];
      }
    }
    if (!singular) return m[0][n] / m[0][0];
  }
  return y.empty() ? 0.0 : y.front();
}

}  // namespace

std::vector<ResponsePoint> smoothed_response(const std::vector<ResponsePoint>& points, int half_window) {
  const std::size_t n = points.size();
  if (half_window <= 0 || n < 3) return points;
  std::vector<double> log_f(n), gain(n), phase(n), weight(n);
  for (std::size_t i = 0; i < n; ++i) {
    log_f[i] = std::log(points[i].freq_hz);
    gain[i] = gain_db(points[i].response);
    double p = phase_deg(points[i].response);
    if (i > 0) p -= 360.0 * std::round((p - phase[i - 1]) / 360.0);  // unwrapped
    phase[i] = p;
    weight[i] = coherence_weight(points[i].coherence);
  }
  std::vector<ResponsePoint> out = points;
  const auto h = static_cast<std::size_t>(half_window);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t lo = i > h ? i - h : 0;
    const std::size_t hi = std::min(n, i + h + 1);
    std::vector<double> t, g, p, w;
    for (std::size_t k = lo; k < hi; ++k) {
      t.push_back(log_f[k] - log_f[i]);
      g.push_back(gain[k]);
      p.push_back(phase[k]);
      w.push_back(weight[k]);
    }
    const double g_db = local_fit_at_zero(t, g, w);
    const double p_deg = local_fit_at_zero(t, p, w);
    out[i].response = std::polar(std::pow(10.0, g_db / 20.0), p_deg * std::numbers::pi / 180.0);
  }
  return out;
}

}  // namespace tnv::tune
