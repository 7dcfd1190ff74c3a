#include "firmware/motion/spindle_synced_feed.hpp"

#include <cmath>

namespace tnv::fw::motion {

double SpindleSyncedFeed::tick(bool at_speed, double measured_rpm, double period_s) noexcept {
  const double rpm = std::fabs(measured_rpm);
  if (!at_speed || !std::isfinite(rpm) || !(period_s > 0.0)) {
    running_ = false;
    filtered_rpm_ = held_rpm_ = 0.0;  // stopped or not at speed: no feed, and nothing kept for later
    return held_rpm_;
  }
  if (!running_) {
    running_ = true;
    filtered_rpm_ = held_rpm_ = rpm;  // at speed now: from this tick's measurement
    return held_rpm_;
  }
  filtered_rpm_ += period_s / (kSyncTauS + period_s) * (rpm - filtered_rpm_);
  if (std::fabs(filtered_rpm_ - held_rpm_) > kSyncBand * held_rpm_) held_rpm_ = filtered_rpm_;
  return held_rpm_;
}

}  // namespace tnv::fw::motion
