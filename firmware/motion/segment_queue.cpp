#include "firmware/motion/segment_queue.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::fw::motion {

namespace {

constexpr double kUnlimited_mm_s = 1e300;

double curvature_per_mm(const SegmentGeometry& g) noexcept {
  return g.kind == SegmentKind::arc_cw || g.kind == SegmentKind::arc_ccw ? 1.0 / g.min_radius_mm() : 0.0;
}

}  // namespace

void SegmentQueue::reset(const MotionLimits& limits, const PlanePoint& start_mm) noexcept {
  limits_ = limits;
  derived_ = derive(limits);
  head_seq_ = 0;
  tail_seq_ = 0;
  end_mm_ = start_mm;
  queued_length_mm_ = 0.0;
}

double SegmentQueue::speed_cap_mm_s(const SegmentGeometry& g) const noexcept {
  const double dt = derived_.dt_s;
  // At least three ticks per element, so one second difference of the path
  // point never spans two corners.
  double cap = std::min(g.axis_speed_cap_mm_s(limits_), g.length_mm / (3.0 * dt));
  const double k = curvature_per_mm(g);
  if (k > 0.0) {
    // Centripetal acceleration v^2/r within the half of the budget the
    // tangential acceleration leaves.
    cap = std::min(cap, std::sqrt(0.5 * derived_.accel_mm_s2 / k));
    // The moving average pulls an arc inwards by about v^2 T^2 / (24 r), T = taps * dt.
    const double window_s = static_cast<double>(derived_.filter_taps) * dt;
    cap = std::min(cap, std::sqrt(24.0 * limits_.path_tolerance_mm / k) / window_s);
  }
  return cap;
}

// A corner turns the path point's velocity from u_a to u_b within one tick:
// per axis the second difference gains v |u_b - u_a|_i dt, on top of the
// tangential change (a half budget) and the centripetal term of an arc.
// The moving average then rounds the corner; with the path speed v at the
// corner the rounded path stays within v sin(theta) T / 8 of the corner's
// two sides (T = taps * dt; docs/motion.md).
double SegmentQueue::corner_limit_mm_s(const QueuedSegment& before, const QueuedSegment& after) const noexcept {
  const PlanePoint& ua = before.geometry.unit_end;
  const PlanePoint& ub = after.geometry.unit_start;
  double du = 0.0;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) du = std::max(du, std::fabs(ub[i] - ua[i]));
  const double dt = derived_.dt_s;
  const double k = std::max(curvature_per_mm(before.geometry), curvature_per_mm(after.geometry));
  const double budget = 0.5 * derived_.accel_mm_s2;
  const double b = du / dt;
  double v = kUnlimited_mm_s;
  if (k > 0.0) v = (-b + std::sqrt(b * b + 4.0 * k * budget)) / (2.0 * k);  // k v^2 + b v = budget
  else if (b > 0.0) v = budget / b;
  const double sin_turn = std::fabs(ua[0] * ub[1] - ua[1] * ub[0]);
  if (sin_turn > 1e-12) {
    const double window_s = static_cast<double>(derived_.filter_taps) * dt;
    v = std::min(v, 8.0 * limits_.path_tolerance_mm / (sin_turn * window_s));
  }
  return v;
}

SegmentRefusal SegmentQueue::push(const Segment& segment) noexcept {
  if (size() >= kSegmentQueueCapacity) return SegmentRefusal::queue_full;
  QueuedSegment q;
  const SegmentRefusal r = prepare(segment, end_mm_, limits_, q.geometry);
  if (r != SegmentRefusal::none) return r;
  q.segment = segment;
  q.speed_cap_mm_s = segment.kind == SegmentKind::dwell ? 0.0 : speed_cap_mm_s(q.geometry);
  q.entry_limit_mm_s = 0.0;
  // From rest after a dwell, an exact stop or a profiled element, and into a profiled one.
  // A rapid into a feed move ends at rest: the feed move may have to wait
  // there for the spindle. The rapid is the queue's last element, planned to
  // end at rest already, so marking it changes no plan in progress.
  if (!empty() && is_feed_move(segment)) {
    QueuedSegment& before = at(tail_seq_ - 1);
    if (before.segment.rapid && before.segment.kind != SegmentKind::dwell) before.segment.exact_stop = true;
  }
  if (!empty() && segment.kind != SegmentKind::dwell && !segment.profiled()) {
    const QueuedSegment& before = at(tail_seq_ - 1);
    if (before.segment.kind != SegmentKind::dwell && !before.segment.exact_stop && !before.segment.profiled())
      q.entry_limit_mm_s = corner_limit_mm_s(before, q);
  }
  q.planned_entry_mm_s = 0.0;  // safe until the look-ahead raises it
  q.planned_hard_mm_s = 0.0;
  at(tail_seq_) = q;
  ++tail_seq_;
  end_mm_ = q.geometry.end_mm;
  queued_length_mm_ += q.geometry.length_mm;
  return SegmentRefusal::none;
}

void SegmentQueue::pop_front() noexcept {
  if (empty()) return;
  queued_length_mm_ -= at(head_seq_).geometry.length_mm;
  ++head_seq_;
  if (empty()) queued_length_mm_ = 0.0;  // no drift of the running sum past an empty queue
}

void SegmentQueue::clear(const PlanePoint& path_point_mm) noexcept {
  end_mm_ = path_point_mm;
  head_seq_ = tail_seq_;
  queued_length_mm_ = 0.0;
}

}  // namespace tnv::fw::motion
