#pragma once
// Moving average over `taps` ticks of the path point, per axis (the same
// length on every axis, so the axes stay in step). If the point's per-axis
// second difference is at most a*dt^2, the output's is too, and the output's
// third difference is at most 2*a*dt^2/taps: with taps >= 2a/(j*dt) the
// commanded jerk stays within j. The average also rounds the point's sharp
// corners into curves within the path tolerance (docs/motion.md).
#include <array>
#include <cstddef>

#include "firmware/motion/motion_limits.hpp"
#include "firmware/motion/segment.hpp"

namespace tnv::fw::motion {

class JerkFilter {
 public:
  // Requires 1 <= taps <= kMaxFilterTaps; fills the history with position_mm.
  void reset(std::size_t taps, const PlanePoint& position_mm) noexcept {
    taps_ = taps;
    next_ = 0;
    for (PlanePoint& p : history_) p = position_mm;
    output_mm_ = position_mm;
    still_ticks_ = taps_;
  }

  const PlanePoint& push(const PlanePoint& point_mm) noexcept {
    still_ticks_ = point_mm == history_[(next_ + taps_ - 1) % taps_] ? still_ticks_ + 1 : 0;
    history_[next_] = point_mm;
    next_ = (next_ + 1) % taps_;
    // Summed afresh every tick (taps additions): no drift from a running sum.
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      double sum = 0.0;
      for (std::size_t k = 0; k < taps_; ++k) sum += history_[k][i];
      output_mm_[i] = sum / static_cast<double>(taps_);
    }
    return output_mm_;
  }

  const PlanePoint& output_mm() const noexcept { return output_mm_; }
  std::size_t taps() const noexcept { return taps_; }
  // The input has not moved for the whole window: the output is at rest.
  bool settled() const noexcept { return still_ticks_ >= taps_; }

 private:
  std::array<PlanePoint, kMaxFilterTaps> history_{};
  std::size_t taps_ = 1;
  std::size_t next_ = 0;
  std::size_t still_ticks_ = 0;
  PlanePoint output_mm_{};
};

}  // namespace tnv::fw::motion
