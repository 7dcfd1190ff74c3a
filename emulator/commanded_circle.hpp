#pragma once
// The nominal circle the experiment commands (reference plant "Circle
// experiment"), evaluated in closed form: counter-clockwise from (R, 0) about
// the origin, one revolution, feed F with raised-cosine ramps of ramp_s at
// both ends. The cutting model needs its feed speed and direction.
#include "emulator/scenario.hpp"

namespace tnv::emu {

struct CirclePathPoint {
  double arc_mm = 0.0;      // path length travelled since the start
  double speed_mm_s = 0.0;  // commanded feed speed
  double cos_angle = 1.0;   // angle theta = arc / R from the +x axis
  double sin_angle = 0.0;
};

class CommandedCircle {
 public:
  enum class Segment { before_start, start_ramp, cruise, end_ramp, after_end };

  explicit CommandedCircle(const CircleParams& params) noexcept;

  double radius_mm() const noexcept { return radius_mm_; }
  double feed_mm_s() const noexcept { return feed_mm_s_; }
  double ramp_s() const noexcept { return ramp_s_; }
  double arc_length_mm() const noexcept { return arc_length_mm_; }  // 2 pi R
  double duration_s() const noexcept { return duration_s_; }        // L / F + ramp_s

  Segment segment_at(double since_start_s) const noexcept {
    if (since_start_s < 0.0) return Segment::before_start;
    if (since_start_s < ramp_s_) return Segment::start_ramp;
    if (since_start_s < end_ramp_start_s_) return Segment::cruise;
    if (since_start_s < duration_s_) return Segment::end_ramp;
    return Segment::after_end;
  }

  // Exact point (uses sin/cos) at a time since the start of motion.
  CirclePathPoint at(double since_start_s) const noexcept;

  // Arc length in the cruise segment (no transcendental functions).
  double cruise_arc_mm(double since_start_s) const noexcept {
    return feed_mm_s_ * (since_start_s - 0.5 * ramp_s_);  // F ramp/2 + F (t - ramp)
  }
  double end_ramp_start_s() const noexcept { return end_ramp_start_s_; }

 private:
  double radius_mm_;
  double feed_mm_s_;
  double ramp_s_;
  double arc_length_mm_;
  double duration_s_;
  double end_ramp_start_s_;
};

}  // namespace tnv::emu
