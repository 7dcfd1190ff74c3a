#pragma once
// The S1 experiment path: a full counter-clockwise circle about the origin
// starting at (R, 0), with raised-cosine feed ramps.
#include <cmath>
#include <cstdint>
#include <numbers>

#include "firmware/trajectory/feed_profile.hpp"
#include "firmware/trajectory/plane_reference.hpp"

namespace tnv::fw {

struct CircleSpec {
  double radius_mm = 6.0;
  double feed_mm_s = 2.0;
  double ramp_s = 0.1;
  double dwell_s = 0.5;  // servo-on hold at the start point before motion
};

// Empty string when valid; otherwise the reason (static text, no allocation).
const char* validate(const CircleSpec& spec) noexcept;

class CircleTrajectory {
 public:
  CircleTrajectory() = default;
  explicit CircleTrajectory(const CircleSpec& spec) noexcept
      : spec_(spec), profile_(2.0 * std::numbers::pi * spec.radius_mm, spec.feed_mm_s, spec.ramp_s) {}

  const CircleSpec& spec() const noexcept { return spec_; }
  double duration_s() const noexcept { return profile_.duration_s(); }

  // t_s: time since the start of motion (the dwell is the caller's business).
  PlaneSample at(double t_s) const noexcept {
    const PathPoint p = profile_.at(t_s);
    const double theta = p.distance_mm / spec_.radius_mm;
    const double c = std::cos(theta);
    const double s = std::sin(theta);
    PlaneSample out;
    out.axis[0] = {spec_.radius_mm * c, -s * p.speed_mm_s};
    out.axis[1] = {spec_.radius_mm * s, c * p.speed_mm_s};
    out.feed_mm_s = p.speed_mm_s;
    return out;
  }

  PlaneSample start() const noexcept { return at(0.0); }

 private:
  CircleSpec spec_{};
  FeedProfile profile_{};
};

}  // namespace tnv::fw
