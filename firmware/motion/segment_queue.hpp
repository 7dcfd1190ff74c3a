#pragma once
// Fixed-capacity ring of prepared segments. push() checks a segment against
// the limits and the end of the previous one, computes its speed caps and
// the corner limit at its start, and either appends it or refuses it with a
// reason and changes nothing.
#include <array>
#include <cstddef>
#include <cstdint>

#include "firmware/motion/motion_limits.hpp"
#include "firmware/motion/segment_geometry.hpp"

namespace tnv::fw::motion {

inline constexpr std::size_t kSegmentQueueCapacity = 64;

struct QueuedSegment {
  Segment segment{};
  SegmentGeometry geometry{};
  double speed_cap_mm_s = 0.0;     // axis speed, centripetal, arc lag and tick-length caps (no feed)
  // The path acceleration on this element (speed changes by it * dt per tick
  // at most): the per-axis envelope less what its start corner's turn and,
  // on an arc, the centripetal acceleration take (docs/motion.md).
  double tangent_accel_mm_s2 = 0.0;
  double entry_limit_mm_s = 0.0;   // corner limit at the start (0 after a stop, a dwell or from rest)
  double planned_entry_mm_s = 0.0; // look-ahead result: can still stop at the end of the queue
  // The same without the programmed feeds (corner limits, speed caps, the
  // queue end): what the path point must obey. A feed is a target: when the
  // override falls while the point brakes for a lower feed ahead, the point
  // slows at the path acceleration and meets that feed a little after the joint.
  double planned_hard_mm_s = 0.0;
};

class SegmentQueue {
 public:
  SegmentQueue() = default;
  // Requires validate(limits) == "". Empties the queue; the path starts at
  // start_mm. path_accel_cap_mm_s2 > 0: no path acceleration above it (the jog's).
  void reset(const MotionLimits& limits, const PlanePoint& start_mm, double path_accel_cap_mm_s2 = 0.0) noexcept;

  SegmentRefusal push(const Segment& segment) noexcept;
  void pop_front() noexcept;
  // Drops every segment; the next pushed one starts at path_point_mm (where the path point rests).
  void clear(const PlanePoint& path_point_mm) noexcept;

  std::size_t size() const noexcept { return static_cast<std::size_t>(tail_seq_ - head_seq_); }
  std::size_t free_slots() const noexcept { return kSegmentQueueCapacity - size(); }
  bool empty() const noexcept { return tail_seq_ == head_seq_; }
  // Absolute sequence numbers: the front is head_seq(), the last is tail_seq() - 1.
  std::uint32_t head_seq() const noexcept { return head_seq_; }
  std::uint32_t tail_seq() const noexcept { return tail_seq_; }
  QueuedSegment& at(std::uint32_t seq) noexcept { return slots_[seq % kSegmentQueueCapacity]; }
  const QueuedSegment& at(std::uint32_t seq) const noexcept { return slots_[seq % kSegmentQueueCapacity]; }
  const PlanePoint& end_mm() const noexcept { return end_mm_; }  // where the next pushed segment starts
  double queued_length_mm() const noexcept { return queued_length_mm_; }  // every queued element's length
  const DerivedLimits& derived() const noexcept { return derived_; }
  const MotionLimits& limits() const noexcept { return limits_; }
  // How fast the path point may speed up on q from speed_mm_s: speeding up
  // is never part of a braking plan, so it takes the whole envelope (a line's
  // direction rate; on an arc what the centripetal term leaves at the new
  // speed), not q's tangent_accel_mm_s2. Near a corner the follower's
  // second-difference check lowers it to what the corner leaves.
  double speed_up_accel_mm_s2(const QueuedSegment& q, double speed_mm_s) const noexcept;

 private:
  double corner_limit_mm_s(const QueuedSegment& before, const QueuedSegment& after) const noexcept;
  double speed_cap_mm_s(const SegmentGeometry& g) const noexcept;
  double tangent_accel_mm_s2(const QueuedSegment& q, const QueuedSegment* before) const noexcept;

  std::array<QueuedSegment, kSegmentQueueCapacity> slots_{};
  std::uint32_t head_seq_ = 0;
  std::uint32_t tail_seq_ = 0;
  PlanePoint end_mm_{};
  double queued_length_mm_ = 0.0;
  MotionLimits limits_{};
  DerivedLimits derived_{};
};

}  // namespace tnv::fw::motion
