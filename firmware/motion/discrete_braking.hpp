#pragma once
// Stopping in whole ticks. The planner moves the path point by v_k * dt per
// tick and changes v by at most a = path_accel * dt per tick, so a stop from
// v runs the speeds v - a, v - 2a, ... down to 0. These functions give the
// exact distance of such a stop and, inversely, the largest speed for this
// tick from which the path point can still stop within a distance: no
// continuous-time approximation, so the queue end is never overrun.
#include <algorithm>
#include <cmath>

namespace tnv::fw::motion {

// Distance of the ticks after this one when braking from speed v_mm_s:
// dt * sum_{j>=1} max(v - j a, 0), with a = dv_per_tick_mm_s.
inline double stop_distance_mm(double v_mm_s, double dv_per_tick_mm_s, double dt_s) noexcept {
  if (v_mm_s <= 0.0) return 0.0;
  const double n = std::floor(v_mm_s / dv_per_tick_mm_s);
  return dt_s * (n * v_mm_s - dv_per_tick_mm_s * n * (n + 1.0) * 0.5);
}

// Largest v such that v * dt + stop_distance_mm(v) <= distance_mm.
inline double stoppable_speed_mm_s(double distance_mm, double dv_per_tick_mm_s, double dt_s) noexcept {
  if (distance_mm <= 0.0) return 0.0;
  const double a = dv_per_tick_mm_s;
  // f(n a) = a dt n (n+1) / 2; find the largest n with f(n a) <= d.
  double n = std::floor(0.5 * (-1.0 + std::sqrt(1.0 + 8.0 * distance_mm / (a * dt_s))));
  if (n < 0.0) n = 0.0;
  // Guard the square root's rounding on either side.
  if (a * dt_s * n * (n + 1.0) * 0.5 > distance_mm) n -= 1.0;
  else if (a * dt_s * (n + 1.0) * (n + 2.0) * 0.5 <= distance_mm) n += 1.0;
  const double v = (distance_mm / dt_s + a * n * (n + 1.0) * 0.5) / (n + 1.0);
  return std::clamp(v, n * a, (n + 1.0) * a);
}

// Largest speed at distance_mm before a point that must be passed at no
// more than exit_mm_s: stop at a virtual point stop_distance(exit) beyond it.
inline double reachable_speed_mm_s(double distance_mm, double exit_mm_s, double dv_per_tick_mm_s,
                                   double dt_s) noexcept {
  return stoppable_speed_mm_s(distance_mm + stop_distance_mm(exit_mm_s, dv_per_tick_mm_s, dt_s), dv_per_tick_mm_s,
                              dt_s);
}

}  // namespace tnv::fw::motion
