#include "emulator/commanded_circle.hpp"

#include <cmath>
#include <numbers>

namespace tnv::emu {

CommandedCircle::CommandedCircle(const CircleParams& params) noexcept
    : radius_mm_(params.radius_mm),
      feed_mm_s_(params.feed_mm_s),
      ramp_s_(params.ramp_s),
      arc_length_mm_(2.0 * std::numbers::pi * params.radius_mm),
      // Each ramp covers F ramp / 2 of arc, so the whole path takes L / F + ramp.
      duration_s_(arc_length_mm_ / params.feed_mm_s + params.ramp_s),
      end_ramp_start_s_(duration_s_ - params.ramp_s) {}

CirclePathPoint CommandedCircle::at(double since_start_s) const noexcept {
  CirclePathPoint point;
  const double t = since_start_s;
  switch (segment_at(t)) {
    case Segment::before_start:
      break;
    case Segment::start_ramp: {
      // speed = F/2 (1 - cos(pi t / ramp)), arc = its integral
      const double phase = std::numbers::pi * t / ramp_s_;
      point.speed_mm_s = 0.5 * feed_mm_s_ * (1.0 - std::cos(phase));
      point.arc_mm = 0.5 * feed_mm_s_ * (t - ramp_s_ / std::numbers::pi * std::sin(phase));
      break;
    }
    case Segment::cruise:
      point.speed_mm_s = feed_mm_s_;
      point.arc_mm = cruise_arc_mm(t);
      break;
    case Segment::end_ramp: {
      const double to_end_s = duration_s_ - t;  // the start ramp, mirrored
      const double phase = std::numbers::pi * to_end_s / ramp_s_;
      point.speed_mm_s = 0.5 * feed_mm_s_ * (1.0 - std::cos(phase));
      point.arc_mm = arc_length_mm_ - 0.5 * feed_mm_s_ * (to_end_s - ramp_s_ / std::numbers::pi * std::sin(phase));
      break;
    }
    case Segment::after_end:
      point.arc_mm = arc_length_mm_;
      break;
  }
  const double angle_rad = point.arc_mm / radius_mm_;
  point.cos_angle = std::cos(angle_rad);
  point.sin_angle = std::sin(angle_rad);
  return point;
}

}  // namespace tnv::emu
