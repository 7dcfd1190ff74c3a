#pragma once
// Runs a MotionInterpolator to rest and measures what a scorer would from
// the commanded positions x_ref,k: per-axis acceleration as the second and
// jerk as the third backward difference over the 1 ms tick, each divided by
// its axis limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "firmware/motion/motion_interpolator.hpp"

namespace tnv::fw::motion::test {

// An interpolator with the default limits, at rest at `start`.
inline MotionInterpolator configured(const PlanePoint& start = {0.0, 0.0}) {
  MotionInterpolator m;
  EXPECT_STREQ(m.configure({}, start), "");
  return m;
}

struct MotionRun {
  std::vector<PlanePoint> position_mm;  // x_ref,k of every axis, one per tick
  double accel_ratio_max = 0.0;
  double jerk_ratio_max = 0.0;
  double speed_ratio_max = 0.0;
  std::size_t motion_ticks = 0;  // from the first tick that moves to the last one
};

inline void score_limits(MotionRun& run, const MotionLimits& limits) {
  const std::vector<PlanePoint>& p = run.position_mm;
  const double dt = limits.tick_period_s;
  for (std::size_t k = 3; k < p.size(); ++k) {
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      const double v = (p[k][i] - p[k - 1][i]) / dt;
      const double a = (p[k][i] - 2.0 * p[k - 1][i] + p[k - 2][i]) / (dt * dt);
      const double j = (p[k][i] - 3.0 * p[k - 1][i] + 3.0 * p[k - 2][i] - p[k - 3][i]) / (dt * dt * dt);
      run.speed_ratio_max = std::max(run.speed_ratio_max, std::fabs(v) / limits.axis[i].speed_mm_s);
      run.accel_ratio_max = std::max(run.accel_ratio_max, std::fabs(a) / limits.axis[i].accel_mm_s2);
      run.jerk_ratio_max = std::max(run.jerk_ratio_max, std::fabs(j) / limits.axis[i].jerk_mm_s3);
    }
  }
  std::size_t first = p.size(), last = 0;
  for (std::size_t k = 1; k < p.size(); ++k) {
    if (p[k] != p[k - 1]) {
      first = std::min(first, k - 1);
      last = k;
    }
  }
  run.motion_ticks = first < p.size() ? last - first : 0;
}

// Ticks until the interpolator is at rest with nothing queued (or max_ticks),
// feeding segments from `program` whenever the queue has room.
template <typename OnTick>
MotionRun run_program(MotionInterpolator& m, const std::vector<Segment>& program, std::size_t max_ticks,
                      OnTick&& on_tick, bool close_program = true) {
  MotionRun run;
  std::size_t next = 0;
  for (std::size_t k = 0; k < max_ticks; ++k) {
    while (next < program.size() && m.free_slots() > 0) {
      if (m.push(program[next]) != SegmentRefusal::none) return run;
      ++next;
    }
    if (close_program && next == program.size()) m.end_program();
    on_tick(k, m);
    const MotionReference ref = m.tick();
    PlanePoint p{};
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) p[i] = ref.axis[i].position_mm;
    run.position_mm.push_back(p);
    if (next == program.size() && m.queued() == 0 && m.at_rest() && k > 4) break;
  }
  score_limits(run, m.limits());
  return run;
}

inline MotionRun run_program(MotionInterpolator& m, const std::vector<Segment>& program,
                             std::size_t max_ticks = 2'000'000) {
  return run_program(m, program, max_ticks, [](std::size_t, MotionInterpolator&) {});
}

// Distance from p to the segment a-b.
inline double distance_to_line_mm(const PlanePoint& p, const PlanePoint& a, const PlanePoint& b) {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0.0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

// Largest distance of the run's samples from the polyline through `corners`.
inline double polyline_deviation_max_mm(const MotionRun& run, const std::vector<PlanePoint>& corners) {
  double worst = 0.0;
  for (const PlanePoint& p : run.position_mm) {
    double best = 1e300;
    for (std::size_t i = 1; i < corners.size(); ++i)
      best = std::min(best, distance_to_line_mm(p, corners[i - 1], corners[i]));
    worst = std::max(worst, best);
  }
  return worst;
}

// The helix tests' helix, measured on a run's reference: radius_mm around
// the origin of the plane (first, second), the height axis falling pitch_mm
// a turn from top_mm. Only the points with the height below from_mm and
// above to_mm count (the plunge before and the retract after do not).
struct HelixFit {
  double radius_worst_mm = 0.0;  // |r - radius|, worst point
  double pitch_worst_mm = 0.0;   // |height - (top - pitch turns)|, worst point
  double turned_rad = 0.0;       // the angle swept, from the start of the first turn
  std::size_t samples = 0;
};

inline HelixFit fit_helix(const std::vector<PlanePoint>& points, std::size_t first, std::size_t second,
                          std::size_t height, double radius_mm, double top_mm, double pitch_mm, double from_mm,
                          double to_mm) {
  HelixFit fit;
  double last_angle = 0.0;
  bool on = false;
  for (const PlanePoint& p : points) {
    const double a = std::atan2(p[second], p[first]);
    if (on) {
      double d = a - last_angle;
      if (d < -std::numbers::pi) d += 2.0 * std::numbers::pi;
      if (d > std::numbers::pi) d -= 2.0 * std::numbers::pi;
      fit.turned_rad += d;
    }
    last_angle = a;
    if (p[height] <= to_mm) break;
    if (!(p[height] < from_mm)) continue;
    if (!on) {  // first point on the helix: its angle from the start of the first turn
      on = true;
      fit.turned_rad = a < 0.0 ? a + 2.0 * std::numbers::pi : a;
    }
    ++fit.samples;
    fit.radius_worst_mm = std::max(fit.radius_worst_mm, std::fabs(std::hypot(p[first], p[second]) - radius_mm));
    const double on_helix_mm = top_mm - pitch_mm * fit.turned_rad / (2.0 * std::numbers::pi);
    fit.pitch_worst_mm = std::max(fit.pitch_worst_mm, std::fabs(p[height] - on_helix_mm));
  }
  return fit;
}

}  // namespace tnv::fw::motion::test
