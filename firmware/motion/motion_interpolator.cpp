#include "firmware/motion/motion_interpolator.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::fw::motion {

const char* MotionInterpolator::configure(const MotionLimits& limits, const PlanePoint& position_mm) noexcept {
  const char* why = validate(limits);
  if (*why != '\0') return why;
  if (!std::isfinite(position_mm[0]) || !std::isfinite(position_mm[1])) return "start position must be finite";
  queue_.reset(limits, position_mm);
  planner_.reset();
  follower_.reset(position_mm);
  filter_.reset(queue_.derived().filter_taps, position_mm);
  out_mm_.fill(position_mm);
  override_ = 1.0;
  hold_ = false;
  stopping_ = false;
  program_open_ = false;
  last_phase_ = FollowerPhase::drained;
  state_ = MotionState::idle;
  stats_ = {};
  return "";
}

SegmentRefusal MotionInterpolator::push(const Segment& segment) noexcept {
  const SegmentRefusal r = queue_.push(segment);
  if (r != SegmentRefusal::none) {
    ++stats_.segments_refused;
    return r;
  }
  ++stats_.segments_accepted;
  program_open_ = true;
  planner_.segment_added(queue_);
  return r;
}

bool MotionInterpolator::set_feed_override(double ratio) noexcept {
  if (!std::isfinite(ratio) || ratio < 0.0 || ratio > kMaxFeedOverride) return false;
  if (ratio != override_) {
    override_ = ratio;
    planner_.override_changed(queue_);
  }
  return true;
}

bool MotionInterpolator::at_rest() const noexcept {
  return follower_.at_rest() && filter_.settled() && out_mm_[0] == out_mm_[3];
}

MotionStats MotionInterpolator::stats() const noexcept {
  MotionStats s = stats_;
  s.follower = follower_.stats();
  return s;
}

MotionReference MotionInterpolator::tick() noexcept {
  stats_.max_replan_examined = std::max(stats_.max_replan_examined, planner_.replan(queue_, override_));
  const FollowerStep step = follower_.step(queue_, override_, hold_ || stopping_);
  if (stopping_ && follower_.at_rest()) {
    queue_.clear(follower_.point_mm());
    planner_.reset();
    stopping_ = false;
    program_open_ = false;
  }
  if (step.phase == FollowerPhase::drained && last_phase_ != FollowerPhase::drained && program_open_)
    ++stats_.underruns;
  last_phase_ = step.phase;

  for (std::size_t i = 0; i + 1 < out_mm_.size(); ++i) out_mm_[i] = out_mm_[i + 1];
  out_mm_[3] = filter_.push(follower_.point_mm());

  if (stopping_) state_ = MotionState::stopping;
  else if (hold_ && !queue_.empty()) state_ = MotionState::holding;
  else if (step.phase != FollowerPhase::drained || !at_rest()) state_ = MotionState::running;
  else state_ = program_open_ ? MotionState::starved : MotionState::idle;

  MotionReference ref;
  const double dt = queue_.derived().dt_s;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    AxisReference& a = ref.axis[i];
    a.position_mm = out_mm_[1][i];
    a.speed_mm_s = (out_mm_[2][i] - out_mm_[0][i]) / (2.0 * dt);
    a.next_position_mm = out_mm_[2][i];
    a.next_speed_mm_s = (out_mm_[3][i] - out_mm_[1][i]) / (2.0 * dt);
  }
  ref.path_speed_mm_s = follower_.speed_mm_s();
  ref.tag = step.tag;
  ref.state = state_;
  return ref;
}

}  // namespace tnv::fw::motion
