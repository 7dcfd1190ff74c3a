#pragma once
// Path length and speed along a move of length L at feed F with
// raised-cosine ramps of duration T_r at start and end (reference plant,
// circle experiment). Each ramp covers F*T_r/2 of path.
#include <cmath>
#include <numbers>

namespace tnv::fw {

struct PathPoint {
  double distance_mm = 0.0;
  double speed_mm_s = 0.0;
};

class FeedProfile {
 public:
  FeedProfile() = default;
  // Requires length > 0, feed > 0, ramp >= 0 and feed*ramp <= length
  // (checked by the owner's validation).
  FeedProfile(double length_mm, double feed_mm_s, double ramp_s) noexcept
      : length_mm_(length_mm), feed_mm_s_(feed_mm_s), ramp_s_(ramp_s),
        cruise_s_(length_mm / feed_mm_s - ramp_s) {}

  double duration_s() const noexcept { return cruise_s_ + 2.0 * ramp_s_; }
  double length_mm() const noexcept { return length_mm_; }

  PathPoint at(double t_s) const noexcept {
    constexpr double pi = std::numbers::pi;
    const double f = feed_mm_s_;
    if (t_s <= 0.0) return {0.0, 0.0};
    if (t_s < ramp_s_) {
      const double w = pi / ramp_s_;
      return {0.5 * f * (t_s - std::sin(w * t_s) / w), 0.5 * f * (1.0 - std::cos(w * t_s))};
    }
    const double ramp_mm = 0.5 * f * ramp_s_;
    if (t_s < ramp_s_ + cruise_s_) return {ramp_mm + f * (t_s - ramp_s_), f};
    const double tau = t_s - ramp_s_ - cruise_s_;
    if (tau < ramp_s_) {
      const double w = pi / ramp_s_;
      return {ramp_mm + f * cruise_s_ + 0.5 * f * (tau + std::sin(w * tau) / w),
              0.5 * f * (1.0 + std::cos(w * tau))};
    }
    return {length_mm_, 0.0};
  }

 private:
  double length_mm_ = 0.0;
  double feed_mm_s_ = 1.0;
  double ramp_s_ = 0.0;
  double cruise_s_ = 0.0;
};

}  // namespace tnv::fw
