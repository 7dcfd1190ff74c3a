#include "firmware/motion/lookahead_planner.hpp"

#include <algorithm>

#include "firmware/motion/discrete_braking.hpp"

namespace tnv::fw::motion {

double feed_limit_mm_s(const QueuedSegment& q, double feed_override) noexcept {
  return std::min(q.speed_cap_mm_s, q.segment.feed_mm_s * feed_override);
}

void LookaheadPlanner::segment_added(const SegmentQueue& queue) noexcept {
  if (queue.empty()) return;
  if (active_) {
    // Let the walk in progress finish (its values stay consistent with the
    // segments behind it), then walk again from the new tail.
    restart_pending_ = true;
    return;
  }
  cursor_seq_ = queue.tail_seq() - 1;
  full_walk_ = false;
  active_ = true;
  starting_ = true;
}

void LookaheadPlanner::override_changed(const SegmentQueue& queue) noexcept {
  if (queue.empty()) return;
  if (active_) {
    restart_pending_ = true;
    full_pending_ = true;
    return;
  }
  cursor_seq_ = queue.tail_seq() - 1;
  full_walk_ = true;
  active_ = true;
  starting_ = true;
}

void LookaheadPlanner::start_walk(const SegmentQueue& queue, bool full, double feed_override) noexcept {
  cursor_seq_ = queue.tail_seq() - 1;
  full_walk_ = full;
  active_ = true;
  walk_override_ = feed_override;
  starting_ = false;
}

std::size_t LookaheadPlanner::replan(SegmentQueue& queue, double feed_override, std::size_t budget) noexcept {
  std::size_t examined = 0;
  const DerivedLimits& d = queue.derived();
  if (active_ && starting_) {
    walk_override_ = feed_override;
    starting_ = false;
  }
  while (active_ && examined < budget) {
    // The front segment's entry is already behind the path point.
    if (queue.empty() || static_cast<std::int32_t>(cursor_seq_ - queue.head_seq()) <= 0 ||
        static_cast<std::int32_t>(cursor_seq_ - queue.tail_seq()) >= 0) {
      active_ = false;
      if (restart_pending_ && !queue.empty()) {
        restart_pending_ = false;
        start_walk(queue, full_pending_, feed_override);
        full_pending_ = false;
        continue;
      }
      break;
    }
    QueuedSegment& q = queue.at(cursor_seq_);
    ++examined;
    double entry = 0.0;
    double hard = 0.0;
    if (q.segment.kind != SegmentKind::dwell) {
      const double dv = q.tangent_accel_mm_s2 * d.dt_s;  // the element's own path acceleration
      double exit = 0.0;
      double exit_hard = 0.0;
      const std::uint32_t next = cursor_seq_ + 1;
      if (!q.segment.exact_stop && next != queue.tail_seq()) {
        exit = queue.at(next).planned_entry_mm_s;
        exit_hard = queue.at(next).planned_hard_mm_s;
      }
      hard = std::min({q.entry_limit_mm_s, q.speed_cap_mm_s,
                       reachable_speed_mm_s(q.geometry.length_mm, exit_hard, dv, d.dt_s)});
      entry = std::min({hard, feed_limit_mm_s(q, walk_override_),
                        reachable_speed_mm_s(q.geometry.length_mm, exit, dv, d.dt_s)});
    }
    const bool unchanged = entry == q.planned_entry_mm_s && hard == q.planned_hard_mm_s;
    q.planned_entry_mm_s = entry;
    q.planned_hard_mm_s = hard;
    --cursor_seq_;
    if (unchanged && !full_walk_) active_ = false;
    if (!active_ && restart_pending_ && !queue.empty()) {
      restart_pending_ = false;
      start_walk(queue, full_pending_, feed_override);
      full_pending_ = false;
    }
  }
  if (!active_) full_walk_ = false;
  return examined;
}

}  // namespace tnv::fw::motion
