#pragma once
// The backward pass of the look-ahead: for every queued segment, the largest
// entry speed from which the path point can still slow to every later corner
// limit and stop at the end of the queue (the last queued segment always
// ends at rest until more arrive). The pass walks from the tail towards the
// front, at most a fixed number of segments per call, so its cost per tick
// is bounded; until it has finished, the older (lower) entry speeds stay in
// force, which is always safe.
#include <cstddef>
#include <cstdint>

#include "firmware/motion/segment_queue.hpp"

namespace tnv::fw::motion {

// Segments examined per replan() call (each an O(1) computation).
inline constexpr std::size_t kReplanBudgetSegments = 8;

class LookaheadPlanner {
 public:
  // After a push: walk back from the new tail until an entry speed no longer changes.
  void segment_added(const SegmentQueue& queue) noexcept;
  // After a feed override change: walk the whole queue again. A walk in
  // progress is never restarted: it finishes (with the override it started
  // with) and the whole queue is walked again after it. A walk restarted
  // from the tail at every change (an override that moves every tick) never
  // reached the front, and a lowered entry behind an entry it never reached
  // asked the path point to brake harder than the limit.
  void override_changed(const SegmentQueue& queue) noexcept;
  void reset() noexcept { active_ = restart_pending_ = full_walk_ = full_pending_ = starting_ = false; }

  // Up to budget segments of the pending walk; returns how many it examined.
  // A walk plans with the override given when it starts (feed_override at
  // that call) and keeps it to its end, so the entries it writes form one
  // consistent braking chain.
  std::size_t replan(SegmentQueue& queue, double feed_override, std::size_t budget = kReplanBudgetSegments) noexcept;
  bool pending() const noexcept { return active_ || restart_pending_; }
  // A walk has started and plans with walk_override(): the follower must not
  // run at a higher override until it is done (its entries may be lowered).
  bool walk_in_progress() const noexcept { return active_ && !starting_; }
  double walk_override() const noexcept { return walk_override_; }

 private:
  void start_walk(const SegmentQueue& queue, bool full, double feed_override) noexcept;

  std::uint32_t cursor_seq_ = 0;  // next segment to examine (walking towards the front)
  bool active_ = false;
  bool full_walk_ = false;
  bool restart_pending_ = false;  // walk again from the tail once the current walk is done
  bool full_pending_ = false;     // ... the whole queue (an override change came in)
  bool starting_ = false;         // a walk was asked for; it takes its override at the next replan()
  double walk_override_ = 1.0;    // the override the current walk plans with
};

// Path speed limit of one segment with the override applied.
double feed_limit_mm_s(const QueuedSegment& q, double feed_override) noexcept;

}  // namespace tnv::fw::motion
