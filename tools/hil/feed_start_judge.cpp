#include "tools/hil/feed_start_judge.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::hil {

bool within_at_speed_window(double speed_rpm, double command_rpm) noexcept {
  return std::fabs(speed_rpm - command_rpm) <= std::max(0.05 * std::fabs(command_rpm), 20.0);
}

bool FeedStartJudge::spindle_ready(const emu::Machine& machine) const noexcept {
  const emu::SpindleTruth s = machine.spindle_truth();
  if (s.command_rpm == 0.0) return true;  // commanded off: feed moves may run (a cut then is a crash)
  return steady_ticks_ >= kSteadyTicks && within_at_speed_window(s.speed_rpm, s.command_rpm);
}

void FeedStartJudge::observe(const emu::Machine& machine, std::size_t front) {
  const double command_rpm = machine.spindle_truth().command_rpm;
  steady_ticks_ = command_rpm == last_command_rpm_ ? steady_ticks_ + 1 : 0;
  last_command_rpm_ = command_rpm;
  double speed_sq = 0.0;
  for (const hal::Axis axis : hal::kAxes) {
    const double v = machine.truth(axis).speed_mm_s;
    speed_sq += v * v;
  }
  const double speed_mm_s = std::sqrt(speed_sq);
  if (speed_mm_s > kMovingMmS && !was_moving_) {
    was_moving_ = true;
    pending_ = MotionOnset{front, spindle_ready(machine)};
    for (const hal::Axis axis : hal::kAxes) from_mm_[hal::index(axis)] = machine.truth(axis).position_mm;
  } else if (speed_mm_s < kRestMmS) {
    was_moving_ = false;
    pending_.reset();  // back at rest without leaving: a twitch
  }
  if (pending_) {
    double moved_sq = 0.0;
    for (const hal::Axis axis : hal::kAxes) {
      const double d = machine.truth(axis).position_mm - from_mm_[hal::index(axis)];
      moved_sq += d * d;
    }
    if (moved_sq > kLeftRestMm * kLeftRestMm) {
      onsets_.push_back(*pending_);
      pending_.reset();
    }
  }
}

FeedStartCount FeedStartJudge::count(const std::vector<fw::motion::Segment>& elements) const noexcept {
  FeedStartCount c;
  for (const MotionOnset& o : onsets_) {
    if (o.front >= elements.size() || !fw::motion::is_feed_move(elements[o.front])) continue;
    ++c.feed_onsets;
    if (!o.spindle_ready) ++c.feed_before_at_speed;
  }
  return c;
}

}  // namespace tnv::hil
