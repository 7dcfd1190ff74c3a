#pragma once
// A known screw for the lead-error tests (tests/tune/screw_fit_test.cpp,
// tests/hil/screw_map_test.cpp): b = 8 um, c = -45 um/m, a first and a
// second harmonic per 10 mm turn, gauged forward and back every 0.625 mm.
#include <cmath>
#include <numbers>
#include <vector>

#include "tools/tune/gauge_point.hpp"

namespace tnv::tune::test {

inline double known_error_um(double p_mm, int d) {
  const double w = 2.0 * std::numbers::pi / 10.0;
  return -45.0 * p_mm * 1e-3 - 0.5 * d * 8.0 + 3.0 * std::sin(w * p_mm) + 1.0 * std::cos(2.0 * w * p_mm) + 7.0;
}

inline std::vector<GaugePoint> known_points() {
  std::vector<GaugePoint> pts;
  for (const int d : {1, -1})
    for (int k = 0; k <= 64; ++k) {
      const double p = -20.0 + 0.625 * k + 0.0001 * d;
      pts.push_back({p, d, p + known_error_um(p, d) * 1e-3});
    }
  return pts;
}

}  // namespace tnv::tune::test
