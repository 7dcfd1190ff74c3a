#pragma once
// The forward half of the planner: once per tick it picks the path point's
// speed (accelerate, cruise at the feed, or brake for the next corner limit
// or the end of the queue), moves the point along the programmed segments,
// and checks that the point's per-axis second difference stays within the
// acceleration budget. The point turns sharp corners; the jerk filter after
// it rounds them (docs/motion.md).
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "firmware/motion/segment_queue.hpp"

namespace tnv::fw::motion {

struct FollowerStats {
  std::uint64_t guard_reductions = 0;  // ticks where the second-difference check lowered the speed
  std::uint64_t guard_failures = 0;    // no speed in the allowed range passed the check (never expected)
  std::uint64_t brake_shortfalls = 0;  // braking needed more than one tick's speed change (never expected)
};

enum class FollowerPhase : std::uint8_t { moving = 0, holding = 1, drained = 2 };

struct FollowerStep {
  FollowerPhase phase = FollowerPhase::drained;
  std::uint32_t tag = 0;  // tag of the segment the point is on
};

class PathFollower {
 public:
  void reset(const PlanePoint& position_mm) noexcept;
  // At rest at position_mm, counts kept (after a profiled element ran).
  void place(const PlanePoint& position_mm) noexcept;

  // hold: brake to rest on the path (feed hold or controlled stop).
  // feed_gate_open false: while the front element is a feed move the point
  // brakes to rest and waits (the spindle is not at speed); a rapid runs.
  // rest_waits: a feed hold (not a stop) also stops the clock of a dwell or
  // an exact stop's settling, so a dwell's remainder waits for the resume.
  FollowerStep step(SegmentQueue& queue, double feed_override, bool hold, bool feed_gate_open = true,
                    bool rest_waits = false) noexcept;

  // A stop during a dwell ends it: at most settle_ticks more (the jerk
  // filter's taps, so its output comes to rest on the point) instead of
  // the dwell's remainder.
  void cut_dwell(std::uint64_t settle_ticks) noexcept { hold_ticks_ = std::min(hold_ticks_, settle_ticks); }

  const PlanePoint& point_mm() const noexcept { return point_mm_; }
  double speed_mm_s() const noexcept { return speed_mm_s_; }
  double distance_on_front_mm() const noexcept { return distance_mm_; }
  bool at_rest() const noexcept { return speed_mm_s_ == 0.0 && hold_ticks_ == 0; }
  std::uint64_t rest_ticks_left() const noexcept { return hold_ticks_; }  // of a dwell or an exact stop's settling
  const FollowerStats& stats() const noexcept { return stats_; }

 private:
  struct Located {
    PlanePoint point_mm{};
    std::uint32_t seq = 0;
    double distance_mm = 0.0;
  };
  Located locate(const SegmentQueue& queue, double ds_mm) const noexcept;
  bool within_budget(const SegmentQueue& queue, const PlanePoint& next_mm) const noexcept;
  void finish_front(SegmentQueue& queue) noexcept;
  double crossing_speed_mm_s(const SegmentQueue& queue, std::uint32_t head, double free_mm_s, double remaining_mm,
                             double feed_override) const noexcept;

  PlanePoint point_mm_{};
  PlanePoint prev_point_mm_{};
  double distance_mm_ = 0.0;  // along the front segment
  double speed_mm_s_ = 0.0;
  std::uint64_t hold_ticks_ = 0;
  std::uint32_t tag_ = 0;
  FollowerStats stats_{};
};

// True when the path point may run from segment seq straight into seq + 1.
bool continues_into_next(const SegmentQueue& queue, std::uint32_t seq) noexcept;

}  // namespace tnv::fw::motion
