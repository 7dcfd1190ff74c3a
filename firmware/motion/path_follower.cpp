#include "firmware/motion/path_follower.hpp"

#include <algorithm>
#include <cmath>

#include "firmware/motion/discrete_braking.hpp"
#include "firmware/motion/lookahead_planner.hpp"

namespace tnv::fw::motion {

namespace {

constexpr double kArrived_mm = 1e-9;
constexpr int kGuardBisections = 10;

}  // namespace

bool continues_into_next(const SegmentQueue& queue, std::uint32_t seq) noexcept {
  const std::uint32_t next = seq + 1;
  if (next == queue.tail_seq()) return false;
  const QueuedSegment& q = queue.at(seq);
  const Segment& after = queue.at(next).segment;
  return !q.segment.exact_stop && q.segment.kind != SegmentKind::dwell && !q.segment.profiled() &&
         after.kind != SegmentKind::dwell && !after.profiled();
}

// The braking curve to a corner asks for v dt + stop(v) <= remaining +
// stop(exit), so a point at the exit speed could never cross a corner in
// the tick it reaches it: every joint between two pieces of a straight
// line cost a small dip in speed. Crossing at `free` (<= the exit speed) is
// safe when the point, free dt - remaining into the next element, can
// still meet that element's own exit: then `free`, else 0 (no change).
double PathFollower::crossing_speed_mm_s(const SegmentQueue& queue, std::uint32_t head, double free_mm_s,
                                         double remaining_mm, double feed_override) const noexcept {
  if (!continues_into_next(queue, head)) return 0.0;
  const DerivedLimits& d = queue.derived();
  const QueuedSegment& next = queue.at(head + 1);
  const double into_next_mm = free_mm_s * d.dt_s - remaining_mm;
  if (into_next_mm >= next.geometry.length_mm) return 0.0;  // two corners in one tick: the old rule
  double next_exit = 0.0;
  if (continues_into_next(queue, head + 1)) {
    const QueuedSegment& after = queue.at(head + 2);
    next_exit = std::min(after.planned_entry_mm_s, feed_limit_mm_s(after, feed_override));
  }
  const double dv = next.tangent_accel_mm_s2 * d.dt_s;
  return free_mm_s <= reachable_speed_mm_s(next.geometry.length_mm - into_next_mm, next_exit, dv, d.dt_s) ? free_mm_s
                                                                                                         : 0.0;
}

void PathFollower::reset(const PlanePoint& position_mm) noexcept {
  point_mm_ = position_mm;
  prev_point_mm_ = position_mm;
  distance_mm_ = 0.0;
  speed_mm_s_ = 0.0;
  hold_ticks_ = 0;
  tag_ = 0;
  stats_ = {};
}

void PathFollower::place(const PlanePoint& position_mm) noexcept {
  const FollowerStats kept = stats_;
  reset(position_mm);
  stats_ = kept;
}

PathFollower::Located PathFollower::locate(const SegmentQueue& queue, double ds_mm) const noexcept {
  Located out;
  out.seq = queue.head_seq();
  out.distance_mm = distance_mm_ + ds_mm;
  while (out.distance_mm > queue.at(out.seq).geometry.length_mm && continues_into_next(queue, out.seq)) {
    out.distance_mm -= queue.at(out.seq).geometry.length_mm;
    ++out.seq;
  }
  const SegmentGeometry& g = queue.at(out.seq).geometry;
  if (out.distance_mm >= g.length_mm) {
    out.distance_mm = g.length_mm;
    out.point_mm = g.end_mm;
  } else {
    out.point_mm = g.point_at(out.distance_mm);
  }
  return out;
}

bool PathFollower::within_budget(const SegmentQueue& queue, const PlanePoint& next_mm) const noexcept {
  const DerivedLimits& d = queue.derived();
  const double dt2 = d.dt_s * d.dt_s * (1.0 + 1e-9);
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {  // each axis within its own limit
    if (std::fabs(next_mm[i] - 2.0 * point_mm_[i] + prev_point_mm_[i]) > d.axis_accel_mm_s2[i] * dt2) return false;
  }
  return true;
}

void PathFollower::finish_front(SegmentQueue& queue) noexcept {
  const QueuedSegment& q = queue.at(queue.head_seq());
  point_mm_ = q.geometry.end_mm;
  // An exact stop rests until the jerk filter's output has reached the corner.
  if (q.segment.exact_stop) hold_ticks_ = queue.derived().filter_taps + 1;
  queue.pop_front();
  distance_mm_ = 0.0;
}

FollowerStep PathFollower::step(SegmentQueue& queue, double feed_override, bool hold, bool feed_gate_open,
                                bool rest_waits) noexcept {
  const PlanePoint here_mm = point_mm_;
  const DerivedLimits& d = queue.derived();
  if (hold_ticks_ > 0) {
    if (!rest_waits) --hold_ticks_;
    prev_point_mm_ = point_mm_;
    speed_mm_s_ = 0.0;
    return {FollowerPhase::holding, tag_};
  }
  // A segment ends at rest here: retire it (and start a dwell) before moving on.
  while (!queue.empty()) {
    const QueuedSegment& front = queue.at(queue.head_seq());
    if (is_program_action(front.segment)) {
      // Stays at the front until released (MotionInterpolator::release_pause(), spindle_change_done()).
      tag_ = front.segment.tag;
      prev_point_mm_ = point_mm_;
      speed_mm_s_ = 0.0;
      return {FollowerPhase::holding, tag_};
    }
    if (front.segment.kind == SegmentKind::dwell) {
      tag_ = front.segment.tag;
      // The filter output rests for the dwell once it has caught up (taps ticks).
      hold_ticks_ = static_cast<std::uint64_t>(std::llround(front.segment.dwell_s / d.dt_s)) + d.filter_taps;
      queue.pop_front();
      prev_point_mm_ = point_mm_;
      speed_mm_s_ = 0.0;
      return {FollowerPhase::holding, tag_};
    }
    const bool at_end = front.geometry.length_mm - distance_mm_ <= kArrived_mm;
    if (at_end && continues_into_next(queue, queue.head_seq())) {
      // Arrived on a corner (a slow one brakes to it): go on from the next segment.
      queue.pop_front();
      distance_mm_ = 0.0;
      continue;
    }
    if (at_end && !continues_into_next(queue, queue.head_seq()) &&
        speed_mm_s_ <= front.tangent_accel_mm_s2 * d.dt_s) {
      finish_front(queue);
      if (hold_ticks_ > 0) {
        prev_point_mm_ = here_mm;
        speed_mm_s_ = 0.0;
        return {FollowerPhase::holding, tag_};
      }
      continue;
    }
    break;
  }
  if (queue.empty()) {
    prev_point_mm_ = here_mm;
    speed_mm_s_ = 0.0;
    return {FollowerPhase::drained, tag_};
  }

  const std::uint32_t head = queue.head_seq();
  const QueuedSegment& front = queue.at(head);
  // Checked after the finished elements are retired: a feed move never
  // starts from rest while the gate is shut, and one already running brakes.
  if (!feed_gate_open && is_feed_move(front.segment)) hold = true;
  const double dv = front.tangent_accel_mm_s2 * d.dt_s;
  const double target = hold ? 0.0 : feed_limit_mm_s(front, feed_override);
  double exit = 0.0;
  double exit_hard = 0.0;  // without the programmed feeds: corner limits, speed caps, the queue end
  if (continues_into_next(queue, head)) {
    const QueuedSegment& next = queue.at(head + 1);
    exit = std::min(next.planned_entry_mm_s, feed_limit_mm_s(next, feed_override));
    exit_hard = next.planned_hard_mm_s;
  }
  const double remaining_mm = front.geometry.length_mm - distance_mm_;
  double brake = reachable_speed_mm_s(remaining_mm, exit, dv, d.dt_s);
  const double free = std::min(speed_mm_s_ + queue.speed_up_accel_mm_s2(front, speed_mm_s_) * d.dt_s, target);
  if (brake < free && free <= exit && free * d.dt_s > remaining_mm)
    brake = std::max(brake, crossing_speed_mm_s(queue, head, free, remaining_mm, feed_override));
  double v = std::min({free, brake});
  const double slowest = std::max(0.0, speed_mm_s_ - dv);
  if (v < slowest) {
    // Braking harder than one tick's change allows. For a programmed feed
    // ahead (a target, lowered by a falling override while the point was
    // already braking for it) the point slows at the allowed rate and meets
    // it just after the joint. Only a corner limit, a speed cap or the queue
    // end would be overrun; the budget was sized so that never happens.
    const double brake_hard = brake < slowest ? reachable_speed_mm_s(remaining_mm, exit_hard, dv, d.dt_s) : brake;
    if (brake_hard < slowest) {
      // Rounding on the exact braking curve leaves femtometres; count real shortfalls only.
      if (brake_hard < slowest - 1e-6 * dv) ++stats_.brake_shortfalls;
      v = brake_hard;
    } else {
      v = slowest;  // a lower feed, override or a hold: slow down at the allowed rate
    }
  }
  Located next = locate(queue, v * d.dt_s);
  if (!within_budget(queue, next.point_mm)) {
    // Lower the speed until the per-axis second difference fits.
    double lo = std::min(slowest, v);
    double hi = v;
    Located best = locate(queue, lo * d.dt_s);
    if (!within_budget(queue, best.point_mm) && lo > 0.0) {
      // Arriving slowly at a sharp corner at the end of a braking run (the
      // last step of a discrete stop may be up to one tick's speed change,
      // above the corner's limit), a stop for this tick may be all that
      // fits: the second difference is then the last step, within the limit.
      const Located rest = locate(queue, 0.0);
      if (within_budget(queue, rest.point_mm)) {
        lo = 0.0;
        best = rest;
      }
    }
    if (within_budget(queue, best.point_mm)) {
      ++stats_.guard_reductions;
      for (int i = 0; i < kGuardBisections; ++i) {
        const double mid = 0.5 * (lo + hi);
        const Located m = locate(queue, mid * d.dt_s);
        if (within_budget(queue, m.point_mm)) {
          lo = mid;
          best = m;
        } else {
          hi = mid;
        }
      }
    } else {
      ++stats_.guard_failures;
    }
    next = best;
    v = lo;
  }
  while (queue.head_seq() != next.seq) queue.pop_front();
  distance_mm_ = next.distance_mm;
  prev_point_mm_ = here_mm;
  point_mm_ = next.point_mm;
  speed_mm_s_ = v;
  tag_ = queue.at(queue.head_seq()).segment.tag;
  return {FollowerPhase::moving, tag_};
}

}  // namespace tnv::fw::motion
