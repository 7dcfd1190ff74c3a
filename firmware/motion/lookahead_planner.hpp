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
  // After a feed override change: walk the whole queue again.
  void override_changed(const SegmentQueue& queue) noexcept;
  void reset() noexcept { active_ = false; restart_pending_ = false; full_walk_ = false; }

  // Up to budget segments of the pending walk; returns how many it examined.
  std::size_t replan(SegmentQueue& queue, double feed_override, std::size_t budget = kReplanBudgetSegments) noexcept;
  bool pending() const noexcept { return active_ || restart_pending_; }

 private:
  std::uint32_t cursor_seq_ = 0;  // next segment to examine (walking towards the front)
  bool active_ = false;
  bool full_walk_ = false;
  bool restart_pending_ = false;
};

// Path speed limit of one segment with the override applied.
double feed_limit_mm_s(const QueuedSegment& q, double feed_override) noexcept;

}  // namespace tnv::fw::motion
