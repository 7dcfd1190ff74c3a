#pragma once
// The reference plant's cutting formulas and the S1 circle, written out
// independently of the emulator for its tests: the table-following model
// for any velocity, and the circle model it generalises (v_feed and the
// feed direction from the commanded circle, what the emulator used before).
#include <cmath>
#include <numbers>

#include "emulator/cutting_disturbance.hpp"
#include "emulator/scenario.hpp"

namespace tnv::emu::test_support {

inline double degrees(double rad) { return rad * 180.0 / std::numbers::pi; }

// Degrees from a velocity to a force, counter-clockwise positive, in (-180, 180].
inline double angle_from_velocity_deg(const CuttingVector& d, double vx, double vy) {
  return degrees(std::atan2(vx * d.y_mm_s - vy * d.x_mm_s, vx * d.x_mm_s + vy * d.y_mm_s));
}

inline CuttingParams cutting_at(double rpm) {
  CuttingParams p;
  p.enabled = true;
  p.spindle_rpm = rpm;
  p.phase_rad = 0.3;
  return p;
}

// (v_feed / F) (900/S)^exponent [c_m + c_a sin(2 pi N S/60 t + phi0)]
inline double cutting_level_mm_s(const CuttingParams& c, double programmed_feed_mm_s, double t_s, double feed_mm_s) {
  const double tooth_rad = 2 * std::numbers::pi * c.flutes * c.spindle_rpm / 60.0 * t_s + c.phase_rad;
  return feed_mm_s / programmed_feed_mm_s * std::pow(900.0 / c.spindle_rpm, c.exponent) *
         (c.mean_mm_s + c.amplitude_mm_s * std::sin(tooth_rad));
}

// d_cut for the table moving at (vx, vy): opposing the travel, rotated 45 deg to its right.
inline CuttingVector direct_cutting(const CuttingParams& c, double programmed_feed_mm_s, double t_s, double vx,
                                    double vy) {
  const double speed = std::hypot(vx, vy);
  if (speed == 0.0) return {};
  const double tx = vx / speed, ty = vy / speed;  // direction of travel
  const double rx = ty, ry = -tx;                 // its right-hand side
  const double level = cutting_level_mm_s(c, programmed_feed_mm_s, t_s, speed);
  return {level * (-tx + rx) / std::sqrt(2.0), level * (-ty + ry) / std::sqrt(2.0)};
}

struct PathSample {
  double x_mm = 0.0, y_mm = 0.0;
  double vx_mm_s = 0.0, vy_mm_s = 0.0;
  double ax_mm_s2 = 0.0, ay_mm_s2 = 0.0;
  double speed_mm_s = 0.0;
  double angle_rad = 0.0;  // theta = arc / R from +x
};

// reference plant "Circle experiment": counter-clockwise from (R, 0), feed F,
// raised-cosine ramps; motion starts at start_s (servo-on + dwell).
struct S1Circle {
  CircleParams circle;
  double start_s = 0.0;

  double duration_s() const { return 2 * std::numbers::pi * circle.radius_mm / circle.feed_mm_s + circle.ramp_s; }

  PathSample at(double t_abs_s) const {
    constexpr double kPi = std::numbers::pi;
    const double F = circle.feed_mm_s, r = circle.ramp_s, T = duration_s(), L = 2 * kPi * circle.radius_mm;
    const double t = t_abs_s - start_s;
    double speed = 0, arc = 0, accel = 0;
    if (t <= 0) {
      arc = 0;
    } else if (t < r) {
      speed = F / 2 * (1 - std::cos(kPi * t / r));
      arc = F / 2 * (t - r / kPi * std::sin(kPi * t / r));
      accel = F / 2 * kPi / r * std::sin(kPi * t / r);
    } else if (t < T - r) {
      speed = F, arc = F * r / 2 + F * (t - r);
    } else if (t < T) {
      const double te = T - t;
      speed = F / 2 * (1 - std::cos(kPi * te / r));
      arc = L - F / 2 * (te - r / kPi * std::sin(kPi * te / r));
      accel = -F / 2 * kPi / r * std::sin(kPi * te / r);
    } else {
      arc = L;
    }
    PathSample p;
    const double R = circle.radius_mm, theta = arc / R, c = std::cos(theta), s = std::sin(theta);
    p.angle_rad = theta;
    p.speed_mm_s = speed;
    p.x_mm = R * c, p.y_mm = R * s;
    p.vx_mm_s = -speed * s, p.vy_mm_s = speed * c;
    // tangential accel along (-s, c), centripetal speed^2 / R toward the centre
    p.ax_mm_s2 = -accel * s - speed * speed / R * c;
    p.ay_mm_s2 = accel * c - speed * speed / R * s;
    return p;
  }
};

// The circle model: v_feed and direction from the commanded circle, u_hat
// opposing the feed rotated 45 deg toward the outward normal.
inline CuttingVector circle_model_cutting(const CuttingParams& c, const CircleParams& circle, double start_s,
                                          double t_s) {
  const PathSample p = S1Circle{circle, start_s}.at(t_s);
  const double level = cutting_level_mm_s(c, circle.feed_mm_s, t_s, p.speed_mm_s);
  const double tx = -std::sin(p.angle_rad), ty = std::cos(p.angle_rad);  // feed direction
  const double nx = std::cos(p.angle_rad), ny = std::sin(p.angle_rad);   // outward normal
  return {level * (-tx + nx) / std::sqrt(2.0), level * (-ty + ny) / std::sqrt(2.0)};
}

// The table-following force against the circle model over the S1 circle's
// motion: rms of the circle model and of the difference, and the means of
// both forces' components along the commanded feed and its outward normal.
class CircleModelComparison {
 public:
  // Both forces at one instant, where the commanded circle is at path_angle_rad.
  void add(const CuttingVector& table, const CuttingVector& circle, double path_angle_rad) {
    const double tx = -std::sin(path_angle_rad), ty = std::cos(path_angle_rad);  // commanded feed
    ++samples_;
    difference_sq_ += std::pow(std::hypot(table.x_mm_s - circle.x_mm_s, table.y_mm_s - circle.y_mm_s), 2);
    circle_sq_ += std::pow(circle.magnitude_mm_s(), 2);
    along_table_ += table.x_mm_s * tx + table.y_mm_s * ty;
    along_circle_ += circle.x_mm_s * tx + circle.y_mm_s * ty;
    outward_table_ += table.x_mm_s * ty - table.y_mm_s * tx;  // (t_y, -t_x): outward on a counter-clockwise circle
    outward_circle_ += circle.x_mm_s * ty - circle.y_mm_s * tx;
  }
  int samples() const { return samples_; }
  double rms_difference_mm_s() const { return std::sqrt(difference_sq_ / samples_); }
  double rms_circle_mm_s() const { return std::sqrt(circle_sq_ / samples_); }
  double along_table_mm_s() const { return along_table_ / samples_; }
  double along_circle_mm_s() const { return along_circle_ / samples_; }
  double outward_table_mm_s() const { return outward_table_ / samples_; }
  double outward_circle_mm_s() const { return outward_circle_ / samples_; }

 private:
  int samples_ = 0;
  double difference_sq_ = 0.0, circle_sq_ = 0.0;
  double along_table_ = 0.0, along_circle_ = 0.0, outward_table_ = 0.0, outward_circle_ = 0.0;
};

}  // namespace tnv::emu::test_support
