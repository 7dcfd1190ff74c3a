#pragma once
// A point-to-point move on one axis: raised-cosine speed ramps (the
// acceleration is a half sine, so it starts and ends at zero: an S-curve)
// around a cruise at constant speed, the same profile as the circle's feed
// ramps (feed_profile.hpp). Move time = |distance| / speed + ramp.
#include <cmath>

#include "firmware/trajectory/feed_profile.hpp"
#include "firmware/trajectory/plane_reference.hpp"
#include "hal/axis.hpp"

namespace tnv::fw {

struct MoveSpec {
  hal::Axis axis = hal::Axis::x;
  double distance_mm = 5.0;  // signed
  double speed_mm_s = 50.0;  // cruise speed, > 0
  double ramp_s = 0.02;      // each speed ramp; the two must fit: speed * ramp <= |distance|
  double dwell_s = 0.0;      // servo-on hold at the start before the move
};

// Empty string when valid; otherwise the reason naming the field (static text).
const char* validate(const MoveSpec& spec) noexcept;

class PointToPointMove {
 public:
  PointToPointMove() = default;
  // Requires validate(spec) == "".
  PointToPointMove(const MoveSpec& spec, double start_mm) noexcept
      : start_mm_(start_mm),
        direction_(spec.distance_mm < 0.0 ? -1.0 : 1.0),
        profile_(std::fabs(spec.distance_mm), spec.speed_mm_s, spec.ramp_s) {}

  double duration_s() const noexcept { return profile_.duration_s(); }
  double start_mm() const noexcept { return start_mm_; }
  double end_mm() const noexcept { return start_mm_ + direction_ * profile_.length_mm(); }

  // t_s since the start of the move; before it the start, after it the end (at rest).
  AxisSample at(double t_s) const noexcept {
    if (t_s >= duration_s()) return {end_mm(), 0.0};  // exactly the end point, exactly at rest
    const PathPoint p = profile_.at(t_s);
    return {start_mm_ + direction_ * p.distance_mm, direction_ * p.speed_mm_s};
  }

 private:
  double start_mm_ = 0.0;
  double direction_ = 1.0;
  FeedProfile profile_{};
};

}  // namespace tnv::fw
