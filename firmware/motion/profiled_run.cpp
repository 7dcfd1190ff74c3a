#include "firmware/motion/profiled_run.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tnv::fw::motion {

void ProfiledRun::start(const SegmentGeometry& g, double feed_mm_s, double ramp_s, double period_s) noexcept {
  geometry_ = g;
  profile_ = FeedProfile(g.length_mm, feed_mm_s, ramp_s);
  ramp_s_ = ramp_s;
  period_s_ = period_s;
  tick_ = 0;
  next_sample_tick_ = -1;
  motion_ticks_ = static_cast<std::int64_t>(std::ceil(profile_.duration_s() / period_s - 1e-9));
  stop_ = {};
  rest_mm_ = g.end_mm;
  active_ = true;
}

// Written as the circle of the S1 experiment was (angle = distance / radius
// from the start angle), so that circle's reference is unchanged.
PathSample ProfiledRun::point_at(double distance_mm, double speed_mm_s) const noexcept {
  const SegmentGeometry& g = geometry_;
  PathSample out;
  if (g.kind == SegmentKind::line) {
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      out.position_mm[i] = g.start_mm[i] + distance_mm * g.unit_start[i];
      out.speed_mm_s[i] = g.unit_start[i] * speed_mm_s;
    }
    return out;
  }
  const double sign = g.sweep_rad >= 0.0 ? 1.0 : -1.0;
  double theta = 0.0;
  double r = g.start_radius_mm;
  if (g.end_radius_mm == g.start_radius_mm) {
    theta = g.start_angle_rad + sign * (distance_mm / r);
  } else {
    const double f = distance_mm / g.length_mm;
    theta = g.start_angle_rad + f * g.sweep_rad;
    r = g.start_radius_mm + f * (g.end_radius_mm - g.start_radius_mm);
  }
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  // In its plane; the other axes stay where the centre is (no helix).
  const PlaneAxes pa = plane_axes(g.plane);
  out.position_mm = g.centre_mm;
  out.position_mm[pa.first] = g.centre_mm[pa.first] + r * c;
  out.position_mm[pa.second] = g.centre_mm[pa.second] + r * s;
  out.speed_mm_s = {};
  out.speed_mm_s[pa.first] = -sign * s * speed_mm_s;
  out.speed_mm_s[pa.second] = sign * c * speed_mm_s;
  return out;
}

PathSample ProfiledRun::at(double t_s) const noexcept {
  if (t_s >= profile_.duration_s()) {
    PathSample end;
    end.position_mm = geometry_.end_mm;  // exactly the end point, exactly at rest
    return end;
  }
  const PathPoint p = profile_.at(t_s);
  return point_at(p.distance_mm, p.speed_mm_s);
}

void ProfiledRun::stop() noexcept {
  if (!active_ || stop_.active) return;
  stop_.active = true;
  stop_.k = 0;
  stop_.n = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::llround(ramp_s_ / period_s_)));
  stop_.tau_s = static_cast<double>(tick_) * period_s_;
}

ProfiledStep ProfiledRun::step() noexcept {
  ProfiledStep out;
  if (!active_) return out;
  PathSample now;
  PathSample next;
  if (stop_.active) {
    const auto rate = [this](std::int64_t k) noexcept {
      return k >= stop_.n ? 0.0
                          : 0.5 * (1.0 + std::cos(std::numbers::pi * static_cast<double>(k) /
                                                   static_cast<double>(stop_.n)));
    };
    next_sample_tick_ = -1;  // the warp samples other times
    const double r_now = rate(stop_.k);
    const double r_next = rate(stop_.k + 1);
    const double tau_next_s = stop_.tau_s + 0.5 * (r_now + r_next) * period_s_;
    now = at(stop_.tau_s);
    next = at(tau_next_s);
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      now.speed_mm_s[i] *= r_now;
      next.speed_mm_s[i] *= r_next;
    }
    out.path_speed_mm_s = profile_.at(stop_.tau_s).speed_mm_s * r_now;
    stop_.tau_s = tau_next_s;
    ++stop_.k;
    out.done = stop_.k >= stop_.n;
  } else {
    const double t_s = static_cast<double>(tick_) * period_s_;
    now = next_sample_tick_ == tick_ ? next_sample_ : at(t_s);
    // x_{k+1} at (k + 1) T, so it is bit for bit next tick's x_k.
    next = at(static_cast<double>(tick_ + 1) * period_s_);
    next_sample_ = next;
    next_sample_tick_ = tick_ + 1;
    out.path_speed_mm_s = profile_.at(t_s).speed_mm_s;
    out.done = tick_ + 1 > motion_ticks_;
  }
  ++tick_;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    out.axis[i] = {now.position_mm[i], now.speed_mm_s[i], next.position_mm[i], next.speed_mm_s[i]};
  if (out.done) {
    rest_mm_ = next.position_mm;
    active_ = false;
    stop_.active = false;
  }
  return out;
}

}  // namespace tnv::fw::motion
