#include "firmware/motion/motion_interpolator.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::fw::motion {

const char* MotionInterpolator::configure(const MotionLimits& limits, const PlanePoint& position_mm) noexcept {
  const char* why = validate(limits);
  if (*why != '\0') return why;
  for (const double v : position_mm)
    if (!std::isfinite(v)) return "start position must be finite";
  limits_ = limits;
  reset_at(position_mm);
  follower_.reset(position_mm);  // and its counts
  stats_ = {};
  return "";
}

void MotionInterpolator::reset_at(const PlanePoint& position_mm, double path_accel_cap_mm_s2) noexcept {
  queue_.reset(limits_, position_mm, path_accel_cap_mm_s2);
  planner_.reset();
  follower_.place(position_mm);
  filter_.reset(queue_.derived().filter_taps, position_mm);
  out_mm_.fill(position_mm);
  profiled_ = ProfiledRun{};
  override_ = effective_override_ = 1.0;
  spindle_factor_ = 1.0;
  hold_ = false;
  feed_gate_open_ = true;
  gate_waiting_ = false;
  stopping_ = false;
  release_front_ = false;
  program_open_ = false;
  last_phase_ = FollowerPhase::drained;
  state_ = MotionState::idle;
  probe_ = ProbeRun{};
  probe_tripped_now_ = false;
  probe_outcome_ = ProbeOutcome::none;
}

void MotionInterpolator::stop() noexcept {
  stopping_ = true;
  profiled_.stop();
  // Nothing moves in a dwell: a stop (abort, host timeout) ends it at once.
  follower_.cut_dwell(queue_.derived().filter_taps);
}

bool MotionInterpolator::front_profiled() const noexcept {
  return !queue_.empty() && queue_.at(queue_.head_seq()).segment.profiled();
}

bool MotionInterpolator::front_pause() const noexcept {
  return !queue_.empty() && queue_.at(queue_.head_seq()).segment.pause;
}

bool MotionInterpolator::front_action() const noexcept {
  return !queue_.empty() && is_program_action(queue_.at(queue_.head_seq()).segment);
}

bool MotionInterpolator::front_probe() const noexcept {
  return !queue_.empty() && queue_.at(queue_.head_seq()).segment.probe != ProbeKind::none;
}

bool MotionInterpolator::probe_before_step() noexcept {
  if (!probe_.queued || stopping_) return false;
  if (front_probe() && !probe_.started) {
    // The element before it ends at rest (an exact stop): the follower
    // holds while the filter's output comes to rest, then the input is checked.
    if (!follower_.at_rest()) return false;
    if (!at_rest()) return true;
    if (probe_trips_on(probe_.kind, probe_input_)) {
      probe_outcome_ = ProbeOutcome::already_tripped;
      probe_ = ProbeRun{};
      stop();  // the program stops: the probe and the end of the program are dropped
      return true;
    }
    probe_.started = true;
  }
  if (probe_.started && !probe_.braking && probe_trips_on(probe_.kind, probe_input_)) {
    probe_.braking = true;
    probe_tripped_now_ = true;
  }
  return false;
}

bool MotionInterpolator::probe_after_step() noexcept {
  if (!probe_.queued || stopping_) return false;
  if (probe_.braking) {
    if (!at_rest()) return false;
    // At rest on the line: the rest of it goes (nothing is queued behind a probe).
    if (front_probe()) ++stats_.segments_done;
    queue_.clear(follower_.point_mm());
    follower_.place(follower_.point_mm());
    planner_.reset();
    probe_outcome_ = ProbeOutcome::tripped;
    probe_ = ProbeRun{};
    last_phase_ = FollowerPhase::drained;  // waiting for the host's next element is no underrun
    return true;
  }
  if (probe_.started && !front_probe()) probe_.left_queue = true;
  if (!probe_.left_queue || !at_rest()) return false;
  probe_outcome_ = probe_end_is_error(probe_.kind) ? ProbeOutcome::failed : ProbeOutcome::not_tripped;
  probe_ = ProbeRun{};
  last_phase_ = FollowerPhase::drained;
  if (is_error(probe_outcome_)) stop();
  return true;
}

bool MotionInterpolator::release_pause() noexcept {
  if (state_ != MotionState::paused) return false;
  release_front_ = true;
  return true;
}

const Segment* MotionInterpolator::spindle_change_due() const noexcept {
  if (release_front_ || stopping_ || hold_ || queue_.empty()) return nullptr;
  const Segment& front = queue_.at(queue_.head_seq()).segment;
  return front.spindle != SpindleChange::none && at_rest() ? &front : nullptr;
}

void MotionInterpolator::spindle_change_done() noexcept {
  if (spindle_change_due() != nullptr) release_front_ = true;
}

SegmentRefusal MotionInterpolator::push(const Segment& segment) noexcept {
  const SegmentRefusal r = probe_.queued ? SegmentRefusal::probe_pending : queue_.push(segment);
  if (r != SegmentRefusal::none) {
    ++stats_.segments_refused;
    return r;
  }
  ++stats_.segments_accepted;
  program_open_ = true;
  if (segment.probe != ProbeKind::none) probe_ = ProbeRun{.queued = true, .kind = segment.probe};
  planner_.segment_added(queue_);
  return r;
}

bool MotionInterpolator::set_feed_override(double ratio) noexcept {
  if (!std::isfinite(ratio) || ratio < 0.0 || ratio > kMaxFeedOverride) return false;
  override_ = ratio;  // in force from the next tick (update_effective_override)
  return true;
}

// Down: at once. A feed target below the path point's speed is met by
// braking at the allowed rate; an exit the lower override drops below the
// braking curve is met just after its joint (the follower then obeys only
// the hard limits, path_follower.cpp). Up: at once, but never above the
// override of a look-ahead walk in progress, whose lowered entries the
// point must still obey. Every walk plans with max(in force, requested),
// never below the override in force, so no walk lowers an entry below a
// feed the follower may be running at.
void MotionInterpolator::update_effective_override() noexcept {
  const double requested = requested_override();
  if (requested == effective_override_) return;
  if (requested < effective_override_) {
    effective_override_ = requested;
  } else {
    const double cap = planner_.walk_in_progress() ? planner_.walk_override() : requested;
    const double floor = effective_override_ > cap ? effective_override_ : cap;
    effective_override_ = requested < floor ? requested : floor;  // min(requested, max(in force, cap)) by value
  }
  planner_.override_changed(queue_);
}

// A feed per revolution at the front runs at feed_mm_rev revolutions' worth
// of the measured speed; its feed_mm_s is the same at the programmed speed.
double MotionInterpolator::spindle_factor() const noexcept {
  const Segment* front = per_rev_front();
  if (front == nullptr) return 1.0;
  const double mm_rev = front->per_rev_along_depth() ? depth_feed_mm_rev_ : front->feed_mm_rev;
  return mm_rev * spindle_rpm_ / 60.0 / front->feed_mm_s;  // feed_mm_s > 0: the queue checked it
}

const Segment* MotionInterpolator::per_rev_front() const noexcept {
  if (queue_.empty() || profiled_.active()) return nullptr;
  const Segment& front = queue_.at(queue_.head_seq()).segment;
  return front.per_rev() ? &front : nullptr;
}

// Along a boring pass's depth: the schedule at the path point's overhang,
// handed on only when it leaves a band of kDepthFeedBand around the one held
// (each change of the override starts a look-ahead walk; S(L) changes
// smoothly, by ~1e-4 a tick at 30 mm/s). NaN (no schedule) stops the feed.
void MotionInterpolator::update_depth_feed() noexcept {
  const Segment* front = per_rev_front();
  if (front == nullptr || !front->per_rev_along_depth()) return;
  constexpr std::size_t z = hal::index(hal::Axis::z);
  const double overhang_mm = front->overhang_at_end_mm - (follower_.point_mm()[z] - front->end_mm[z]);  // deeper: longer
  const double s = depth_infeed_.at(overhang_mm);
  if (!std::isfinite(s)) {
    depth_feed_mm_rev_ = 0.0;
  } else if (!(std::fabs(s - depth_feed_mm_rev_) <= kDepthFeedBand * depth_feed_mm_rev_)) {
    depth_feed_mm_rev_ = s;
  }
}

double MotionInterpolator::requested_override() const noexcept {
  const double r = override_ * spindle_factor_;
  return std::isfinite(r) ? std::min(r, kMaxFeedOverride) : 0.0;
}

double MotionInterpolator::running_feed_mm_s() const noexcept {
  if (hold_ || stopping_ || queue_.empty() || profiled_.active()) return 0.0;
  const Segment& front = queue_.at(queue_.head_seq()).segment;
  return front.kind == SegmentKind::dwell || front.profiled() ? 0.0 : front.feed_mm_s;
}

bool MotionInterpolator::at_rest() const noexcept {
  return !profiled_.active() && follower_.at_rest() && filter_.settled() && out_mm_[0] == out_mm_[3];
}

MotionStats MotionInterpolator::stats() const noexcept {
  MotionStats s = stats_;
  s.follower = follower_.stats();
  return s;
}

// The profiled element at the front has the path to itself: it starts once
// everything before it rests on its start point, and when it is done the
// planner's path point, filter and output rest where it ended.
MotionReference MotionInterpolator::profiled_tick() noexcept {
  const ProfiledStep step = profiled_.step();
  if (step.done) finish_profiled();
  MotionReference ref;
  ref.axis = step.axis;
  ref.path_speed_mm_s = step.path_speed_mm_s;
  ref.tag = queue_.empty() ? 0 : queue_.at(queue_.head_seq()).segment.tag;
  if (stopping_ && !profiled_.active()) {
    stopping_ = false;
    program_open_ = false;
  }
  if (profiled_.active()) state_ = profiled_.stopping() ? MotionState::stopping : MotionState::running;
  else if (!queue_.empty()) state_ = MotionState::running;
  else state_ = program_open_ ? MotionState::starved : MotionState::idle;
  ref.state = state_;
  return ref;
}

void MotionInterpolator::finish_profiled() noexcept {
  const PlanePoint rest = profiled_.rest_mm();
  ++stats_.segments_done;
  if (stopping_) {
    queue_.clear(rest);  // a stop drops the rest of the queue
    planner_.reset();
  } else {
    queue_.pop_front();
  }
  follower_.place(rest);
  filter_.reset(queue_.derived().filter_taps, rest);
  out_mm_.fill(rest);
  last_phase_ = FollowerPhase::holding;  // running dry from here on is an underrun of an open program
}

MotionReference MotionInterpolator::tick() noexcept {
  gate_waiting_ = false;
  probe_tripped_now_ = false;
  probe_outcome_ = ProbeOutcome::none;
  if (profiled_.active()) return profiled_tick();
  const bool front_gated =
      !feed_gate_open_ && !queue_.empty() && is_feed_move(queue_.at(queue_.head_seq()).segment);
  if (front_profiled() && at_rest() && (stopping_ || !front_gated)) {
    if (stopping_) {
      queue_.clear(follower_.point_mm());  // stopped before it began
      follower_.place(follower_.point_mm());
      planner_.reset();
    } else {
      const QueuedSegment& q = queue_.at(queue_.head_seq());
      profiled_.start(q.geometry, q.segment.feed_mm_s, q.segment.ramp_s, queue_.derived().dt_s);
      return profiled_tick();
    }
  }
  if (release_front_) {
    release_front_ = false;
    if (front_action() && !stopping_) {
      queue_.pop_front();
      ++stats_.segments_done;
    }
  }
  update_depth_feed();
  spindle_factor_ = spindle_factor();
  update_effective_override();
  const double walk_override = std::max(effective_override_, requested_override());
  stats_.max_replan_examined = std::max(stats_.max_replan_examined, planner_.replan(queue_, walk_override));
  // A profiled element, and a probe, wait at the front while the reference comes to rest on its start.
  const bool wait = probe_before_step() || front_profiled();
  const std::size_t queued_before = queue_.size();
  const FollowerStep step = wait ? FollowerStep{FollowerPhase::holding, queue_.at(queue_.head_seq()).segment.tag}
                                 : follower_.step(queue_, effective_override_, hold_ || stopping_ || probe_.braking,
                                                  feed_gate_open_, hold_ && !stopping_);
  gate_waiting_ = !feed_gate_open_ && !queue_.empty() && is_feed_move(queue_.at(queue_.head_seq()).segment);
  if (queue_.size() < queued_before) stats_.segments_done += queued_before - queue_.size();
  if (stopping_ && follower_.at_rest()) {
    probe_ = ProbeRun{};  // a probe goes with the queue, without an outcome
    queue_.clear(follower_.point_mm());
    follower_.place(follower_.point_mm());  // its distance along the dropped front goes with it
    planner_.reset();
    stopping_ = false;
    program_open_ = false;
  }
  if (step.phase == FollowerPhase::drained && last_phase_ != FollowerPhase::drained && program_open_)
    ++stats_.underruns;
  last_phase_ = step.phase;

  for (std::size_t i = 0; i + 1 < out_mm_.size(); ++i) out_mm_[i] = out_mm_[i + 1];
  out_mm_[3] = filter_.push(follower_.point_mm());
  // A probe decided at rest leaves nothing queued: the state is the host's wait already.
  const FollowerPhase phase = probe_after_step() ? FollowerPhase::drained : step.phase;

  if (stopping_) state_ = MotionState::stopping;
  else if (hold_ && (!queue_.empty() || follower_.rest_ticks_left() > 0)) state_ = MotionState::holding;
  else if (front_pause() && at_rest()) state_ = MotionState::paused;
  else if (phase != FollowerPhase::drained || !at_rest()) state_ = MotionState::running;
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
