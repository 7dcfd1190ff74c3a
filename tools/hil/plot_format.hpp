#pragma once
// Number formatting and axis steps shared by the SVG figures.
#include <cmath>
#include <cstdio>
#include <string>

namespace tnv::hil {

// printf-style formatting of one value for an axis label or legend.
inline std::string format_value(const char* pattern, double v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, pattern, v);
  return buf;
}

// A 1, 2 or 5 times a power of ten at least span / target_ticks (span > 0).
inline double nice_step(double span, int target_ticks) {
  const double raw = span / target_ticks;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10.0 * p;
}

}  // namespace tnv::hil
