#include "tools/tune/bode_margins.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace tnv::tune {

namespace {

// Gain dB and the phase unwrapped along the points (deg), at each point.
struct Unwrapped {
  std::vector<double> log_f, gain_db, phase_deg;
};

Unwrapped unwrap(const std::vector<ResponsePoint>& points) {
  Unwrapped u;
  double previous = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    double ph = phase_deg(points[i].response);
    if (i > 0) ph += 360.0 * std::round((previous - ph) / 360.0);
    previous = ph;
    u.log_f.push_back(std::log(points[i].freq_hz));
    u.gain_db.push_back(gain_db(points[i].response));
    u.phase_deg.push_back(ph);
  }
  return u;
}

double lerp(double a, double b, double t) { return a + (b - a) * t; }

// Phase margin in (-180, 180] from an unwrapped phase.
double wrap_margin(double phase) {
  double pm = std::fmod(180.0 + phase, 360.0);
  if (pm <= -180.0) pm += 360.0;
  if (pm > 180.0) pm -= 360.0;
  return pm;
}

}  // namespace

BodeMargins margins_from_points(const std::vector<ResponsePoint>& open_loop) {
  BodeMargins m;
  m.gain_margin_db = std::numeric_limits<double>::infinity();
  double pm_smallest = std::numeric_limits<double>::infinity();
  const Unwrapped u = unwrap(open_loop);
  for (std::size_t i = 1; i < open_loop.size(); ++i) {
    const double g0 = u.gain_db[i - 1], g1 = u.gain_db[i];
    if ((g0 > 0.0) != (g1 > 0.0) && g1 != g0) {
      const double t = g0 / (g0 - g1);
      const double pm = wrap_margin(lerp(u.phase_deg[i - 1], u.phase_deg[i], t));
      m.crossover_found = true;
      m.crossover_hz = std::exp(lerp(u.log_f[i - 1], u.log_f[i], t));  // the highest, by the scan's order
      pm_smallest = std::fmin(pm_smallest, pm);
    }
    // Phase crossings of -180 + k 360 between the two points.
    const double p0 = u.phase_deg[i - 1], p1 = u.phase_deg[i];
    const double k0 = std::floor((p0 + 180.0) / 360.0), k1 = std::floor((p1 + 180.0) / 360.0);
    if (k0 != k1) {
      const double level = -180.0 + 360.0 * std::fmax(k0, k1);
      const double t = (level - p0) / (p1 - p0);
      const double g = lerp(g0, g1, t);
      if (g < 0.0 && -g < m.gain_margin_db) {
        m.gain_margin_db = -g;
        m.phase_crossover_hz = std::exp(lerp(u.log_f[i - 1], u.log_f[i], t));
      }
    }
  }
  m.phase_margin_deg = m.crossover_found ? pm_smallest : 0.0;
  return m;
}

double bandwidth_hz(const std::vector<ResponsePoint>& closed_loop) {
  if (closed_loop.empty()) return std::numeric_limits<double>::quiet_NaN();
  const Unwrapped u = unwrap(closed_loop);
  const double level = u.gain_db[0] - 3.0;
  for (std::size_t i = 1; i < closed_loop.size(); ++i)
    if (u.gain_db[i] < level) {
      const double t = (level - u.gain_db[i - 1]) / (u.gain_db[i] - u.gain_db[i - 1]);
      return std::exp(lerp(u.log_f[i - 1], u.log_f[i], t));
    }
  return std::numeric_limits<double>::quiet_NaN();
}

std::vector<ResponsePoint> closed_from_open(const std::vector<ResponsePoint>& open_loop) {
  std::vector<ResponsePoint> out = open_loop;
  for (ResponsePoint& p : out) p.response = p.response / (1.0 + p.response);
  return out;
}

}  // namespace tnv::tune
