#pragma once
// The motion core the tick runs: a segment queue, the look-ahead planner
// (bounded backward pass + per-tick path follower) and the jerk filter.
// Producers push() segments; the tick calls tick() once per period and feeds
// the result's x_ref,k and x_ref,k+1 to the axis loops. Everything is fixed
// size: no allocation, no exceptions, no locks.
#include <array>
#include <cstddef>
#include <cstdint>

#include "firmware/adaptive/boring/infeed_schedule.hpp"
#include "firmware/control/axis_controller.hpp"
#include "firmware/motion/jerk_filter.hpp"
#include "firmware/motion/lookahead_planner.hpp"
#include "firmware/motion/path_follower.hpp"
#include "firmware/motion/profiled_run.hpp"
#include "firmware/motion/segment_queue.hpp"

namespace tnv::fw::motion {

inline constexpr double kDepthFeedBand = 0.0025;  // relative: a per-rev line along the depth's infeed steps

enum class MotionState : std::uint8_t {
  idle = 0,      // nothing queued, reference at rest
  running = 1,
  holding = 2,   // feed hold: braking or at rest on the path, queue kept
  stopping = 3,  // controlled stop: braking on the path, then the queue is dropped
  starved = 4,   // the queue ran dry before the program's end: at rest on the path, resumes on push
  paused = 5,    // at rest at a program pause (Segment::pause) until release_pause()
};

constexpr const char* to_string(MotionState s) noexcept {
  switch (s) {
    case MotionState::idle: return "idle";
    case MotionState::running: return "running";
    case MotionState::holding: return "holding";
    case MotionState::stopping: return "stopping";
    case MotionState::starved: return "starved";
    case MotionState::paused: return "paused";
  }
  return "?";
}

struct MotionReference {
  std::array<AxisReference, hal::kAxisCount> axis{};  // x_ref,k and x_ref,k+1 per axis
  double path_speed_mm_s = 0.0;  // the planner's path speed (before the jerk filter)
  std::uint32_t tag = 0;         // tag of the segment being run
  MotionState state = MotionState::idle;
};

struct MotionStats {
  std::uint64_t underruns = 0;            // queue ran dry while the program was open
  std::uint64_t segments_done = 0;        // elements finished (left the queue), dwells included
  std::uint64_t segments_accepted = 0;
  std::uint64_t segments_refused = 0;
  std::size_t max_replan_examined = 0;    // most segments one tick's backward pass examined
  FollowerStats follower{};
};

class MotionInterpolator {
 public:
  // Empty string when the limits are valid (the interpolator is then reset
  // at position_mm, at rest); otherwise the reason, and nothing changes.
  const char* configure(const MotionLimits& limits, const PlanePoint& position_mm) noexcept;
  // The configured limits, everything dropped: at rest at position_mm,
  // override 1, no hold, program closed. Counts are kept. With
  // path_accel_cap_mm_s2 > 0 (the jog's own acceleration limit) the path
  // acceleration of what follows is at most that (the axis limits still hold).
  void reset_at(const PlanePoint& position_mm, double path_accel_cap_mm_s2 = 0.0) noexcept;

  SegmentRefusal push(const Segment& segment) noexcept;
  std::size_t free_slots() const noexcept { return queue_.free_slots(); }
  std::size_t queued() const noexcept { return queue_.size(); }
  // Path still queued ahead of the path point (the rest of the front element and all after it).
  double queued_path_mm() const noexcept { return queue_.queued_length_mm() - follower_.distance_on_front_mm(); }
  // Where the next pushed element starts.
  const PlanePoint& queue_end_mm() const noexcept { return queue_.end_mm(); }

  // 0 ... 1.5; false (and no change) outside that range or not finite.
  // The override in force (effective_feed_override()) follows it at the
  // next tick: a lower one at once, a higher one at once unless a look-ahead
  // walk planned with a lower override is in progress (it then applies when
  // that walk is done, a few ticks): the follower never runs at a higher
  // override than the entries it obeys were planned with. A walk in
  // progress is never restarted by an override change (lookahead_planner.hpp).
  bool set_feed_override(double ratio) noexcept;
  double feed_override() const noexcept { return override_; }
  // The override the planner and the follower use this tick.
  double effective_feed_override() const noexcept { return effective_override_; }
  // The programmed feed of the planned line or arc at the front, which the
  // override scales; 0 while the path does not run on one (empty queue, a
  // dwell or a profiled element in front, feed hold, a controlled stop).
  double running_feed_mm_s() const noexcept;

  // The spindle speed a feed per revolution (Segment::per_rev()) runs at,
  // set before each tick() (SpindleSyncedFeed: measured, 0 while not at
  // speed). While one is at the front the override in force is the
  // requested one times feed_mm_rev * rpm / 60 / feed_mm_s (measured over
  // programmed spindle speed, up to kMaxFeedOverride in all), so the path
  // follows the spindle through the override's path and its limits; 0 rpm
  // brakes it to rest on the path, where it waits. 1 for other elements.
  void set_spindle_rpm(double rpm) noexcept { spindle_rpm_ = rpm; }
  double spindle_feed_factor() const noexcept { return spindle_factor_; }
  // The node's boring schedule a feed per revolution along the depth
  // (Segment::per_rev_along_depth()) takes its infeed from, at the path
  // point's overhang every tick (within kDepthFeedBand). Unset: such a line
  // does not move. reset_at() keeps it.
  void set_depth_infeed(const InfeedAlongOverhang& schedule) noexcept { depth_infeed_ = schedule; }
  const InfeedAlongOverhang& depth_infeed() const noexcept { return depth_infeed_; }
  // The infeed (mm/rev) a line along the depth runs at now.
  double depth_feed_mm_rev() const noexcept { return depth_feed_mm_rev_; }

  // The spindle's feed gate (firmware/spindle/spindle_control.hpp
  // feed_permitted()), set before each tick(): while it is shut a feed move
  // (is_feed_move(): a line or arc that is not a rapid, a profiled element
  // included) does not start, and a planned one running brakes to rest on
  // the path; it goes on when the gate opens. Rapids and dwells run. reset_at() opens it.
  void set_feed_gate(bool open) noexcept { feed_gate_open_ = open; }
  bool feed_gate_open() const noexcept { return feed_gate_open_; }
  // The last tick held a feed move at the gate (at rest or braking for it).
  bool waiting_for_feed_gate() const noexcept { return gate_waiting_; }

  // The touch probe input (the board's, sampled at this tick's latch), set
  // before each tick(). Only a probe move (Segment::probe) looks at it: it
  // starts once everything rests at its start, refused (already_tripped,
  // and the program stops) when the input is then in the state that would
  // end it; running, the first tick that sees that state is the trip
  // (probe_tripped_now()): the path point brakes to rest on the line at
  // the path acceleration, the rest of the line is dropped and the next
  // element starts where it rests. Untripped at the end (the reference at
  // rest there), G38.3/G38.5 go on and G38.2/G38.4 stop the program.
  void set_probe_input(bool touching) noexcept { probe_input_ = touching; }
  // This tick saw the probe's trip (the tick task latches the measured position now).
  bool probe_tripped_now() const noexcept { return probe_tripped_now_; }
  // A probe move's outcome, in the tick it was decided (none otherwise):
  // at rest after a trip, at rest at an untripped end, or at the refused start.
  ProbeOutcome probe_outcome() const noexcept { return probe_outcome_; }
  // A probe move is queued or running: push() refuses (probe_pending) until its outcome.
  bool probe_pending() const noexcept { return probe_.queued; }

  // A program pause at the front (Segment::pause) with everything at rest
  // (state() paused): the next tick drops it and the program goes on. false
  // (nothing changes) when not paused. A feed hold or a stop is not a pause:
  // neither is released here, and a pause is not left by resume().
  bool release_pause() noexcept;
  // A spindle command (Segment::spindle) at the front with everything at
  // rest, no hold and no stop: the tick task carries it out and calls
  // spindle_change_done(), and the next tick drops it. nullptr otherwise.
  const Segment* spindle_change_due() const noexcept;
  void spindle_change_done() noexcept;

  void hold() noexcept { hold_ = true; }
  void resume() noexcept { hold_ = false; }
  // Brake on the path; once at rest, drop whatever is still queued. A
  // profiled element stops by its time warp (profiled_run.hpp); hold and
  // the feed override act on planned elements only.
  void stop() noexcept;
  // The producer has sent its last segment: running dry now is the end, not an underrun.
  void end_program() noexcept { program_open_ = false; }

  // Once per tick.
  MotionReference tick() noexcept;

  MotionState state() const noexcept { return state_; }
  // A profiled element is running (the circle or move of the producers).
  bool profiled_running() const noexcept { return profiled_.active(); }
  const ProfiledRun& profiled() const noexcept { return profiled_; }
  // Where the reference rests when state() is idle: the last x_ref,k+1.
  PlanePoint reference_mm() const noexcept { return out_mm_[2]; }
  double path_speed_mm_s() const noexcept { return follower_.speed_mm_s(); }
  bool at_rest() const noexcept;  // planner and filter output both at rest, no profiled element running
  MotionStats stats() const noexcept;
  const DerivedLimits& derived() const noexcept { return queue_.derived(); }
  const MotionLimits& limits() const noexcept { return limits_; }

 private:
  MotionReference profiled_tick() noexcept;
  void update_effective_override() noexcept;
  double spindle_factor() const noexcept;       // for the element at the front
  const Segment* per_rev_front() const noexcept;  // the front element if it is fed per revolution, else null
  void update_depth_feed() noexcept;
  double requested_override() const noexcept;   // override_ times spindle_factor_, capped
  bool front_profiled() const noexcept;
  bool front_pause() const noexcept;
  bool front_action() const noexcept;
  void finish_profiled() noexcept;
  bool front_probe() const noexcept;
  // Before the follower's step: start, refuse or trip the probe at the front. True: the follower waits.
  bool probe_before_step() noexcept;
  // After it: a tripped probe at rest leaves the queue; an untripped one at
  // rest at its end is decided. True when an outcome was decided this tick.
  bool probe_after_step() noexcept;

  MotionLimits limits_{};
  SegmentQueue queue_{};
  LookaheadPlanner planner_{};
  PathFollower follower_{};
  JerkFilter filter_{};
  ProfiledRun profiled_{};
  std::array<PlanePoint, 4> out_mm_{};  // filter output at k-1, k, k+1, k+2
  double override_ = 1.0;            // requested
  double effective_override_ = 1.0;  // in force (update_effective_override)
  double spindle_rpm_ = 0.0;         // set_spindle_rpm
  double spindle_factor_ = 1.0;      // this tick's, for a feed per revolution at the front
  InfeedAlongOverhang depth_infeed_{};  // set_depth_infeed
  double depth_feed_mm_rev_ = 0.0;      // held by update_depth_feed()
  bool hold_ = false;
  bool feed_gate_open_ = true;
  bool gate_waiting_ = false;
  bool stopping_ = false;
  bool release_front_ = false;  // release_pause() / spindle_change_done(): the front leaves the queue at the next tick
  bool program_open_ = false;
  FollowerPhase last_phase_ = FollowerPhase::drained;
  // The probe move in the queue, if any (probe_move.hpp).
  struct ProbeRun {
    bool queued = false;    // pushed, outcome not yet known
    bool started = false;   // its input was checked at rest at its start
    bool braking = false;   // tripped: braking to rest on the line
    bool left_queue = false;  // reached its end untripped: waiting for the reference to rest there
    ProbeKind kind = ProbeKind::none;
  };
  ProbeRun probe_{};
  bool probe_input_ = false;
  bool probe_tripped_now_ = false;
  ProbeOutcome probe_outcome_ = ProbeOutcome::none;
  MotionState state_ = MotionState::idle;
  MotionStats stats_{};  // follower counts are added by stats()
};

}  // namespace tnv::fw::motion
