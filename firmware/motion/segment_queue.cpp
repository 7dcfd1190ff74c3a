#include "firmware/motion/segment_queue.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::fw::motion {

namespace {

constexpr double kUnlimited_mm_s = 1e300;

double curvature_per_mm(const SegmentGeometry& g) noexcept {
  return g.kind == SegmentKind::arc_cw || g.kind == SegmentKind::arc_ccw ? 1.0 / g.min_radius_mm() : 0.0;
}

// An arc may run along any axis of its plane: the smallest of their limits.
double arc_axis_accel_mm_s2(const DerivedLimits& d) noexcept {
  double a = d.axis_accel_mm_s2[0];
  for (const double ai : d.axis_accel_mm_s2) a = std::min(a, ai);
  return a;
}

// Largest v >= 0 with k v^2 + b v <= room (k, b >= 0).
double quadratic_speed_mm_s(double k, double b, double room) noexcept {
  if (room <= 0.0) return 0.0;
  if (k > 0.0) return 2.0 * room / (b + std::sqrt(b * b + 4.0 * k * room));  // the root, without cancellation
  if (b > 0.0) return room / b;
  return kUnlimited_mm_s;
}

}  // namespace

void SegmentQueue::reset(const MotionLimits& limits, const PlanePoint& start_mm, double path_accel_cap_mm_s2) noexcept {
  limits_ = limits;
  derived_ = derive(limits, path_accel_cap_mm_s2);
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
    // Centripetal acceleration v^2/r within its share of the plane's axes,
    // so the tangential acceleration keeps the rest (tangent_accel_mm_s2).
    cap = std::min(cap, std::sqrt(kCentripetalShare * arc_axis_accel_mm_s2(derived_) / k));
    // The moving average pulls an arc inwards by about v^2 T^2 / (24 r), T = taps * dt.
    const double window_s = static_cast<double>(derived_.filter_taps) * dt;
    cap = std::min(cap, std::sqrt(24.0 * limits_.path_tolerance_mm / k) / window_s);
  }
  return cap;
}

// The path acceleration of an element. An arc: tangential t and centripetal
// c are perpendicular, so on every axis of its plane |t u_i + c n_i| <=
// sqrt(t^2 + c^2), kept within kTangentShare of the smallest limit at the
// fastest the arc may run (its cap, or its feed at the highest override).
// A line: the per-direction envelope; after a line corner it leaves each
// axis the room the corner's turn needs at the lower feed, unless that
// would cost more than kTangentFloorShare of it (then the corner is slow).
double SegmentQueue::tangent_accel_mm_s2(const QueuedSegment& q, const QueuedSegment* before) const noexcept {
  const SegmentGeometry& g = q.geometry;
  const double k = curvature_per_mm(g);
  if (k > 0.0) {
    const double plane = arc_axis_accel_mm_s2(derived_);
    const double v_top = std::min(q.speed_cap_mm_s, q.segment.feed_mm_s * kMaxFeedOverride);
    const double a = kTangentShare * plane;
    const double c = std::min(k * v_top * v_top, kCentripetalShare * plane);
    return std::min(std::sqrt(a * a - c * c), derived_.path_accel_cap_mm_s2);
  }
  const double full = line_accel_mm_s2(derived_, g.unit_start);
  if (before == nullptr || curvature_per_mm(before->geometry) > 0.0) return full;
  const double v = std::min({q.segment.feed_mm_s, before->segment.feed_mm_s, q.speed_cap_mm_s, before->speed_cap_mm_s});
  const PlanePoint& ua = before->geometry.unit_end;
  const PlanePoint& ub = g.unit_start;
  // The corner at the line's end is not known yet, but this line's rate
  // binds there too (corner_limit_mm_s takes the larger side's). Assume it
  // turns as the one at its start, in the same plane (the next chord of a
  // polyline circle): u_next = 2 (u_a . u_b) u_b - u_a. Without it, a chord
  // sized for the gentler turn behind it left the next corner a few mm/s^2
  // short, and where an axis' turn share is small that cost mm/s of speed.
  double cos_turn = 0.0;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) cos_turn += ua[i] * ub[i];
  double target = full;
  bool feasible = true;
  const double floor = kTangentFloorShare * full;
  double v_floor = kUnlimited_mm_s;  // the corner's speed when the line keeps only the floor share
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const double du = std::max(std::fabs(ub[i] - ua[i]), std::fabs((2.0 * cos_turn - 1.0) * ub[i] - ua[i]));
    const double room = derived_.axis_accel_mm_s2[i] - v * du / derived_.dt_s;
    const double u = std::fabs(g.unit_start[i]);
    feasible = feasible && room > 0.0;  // else not even all of the axis turns it at that feed
    if (u > 1e-12) target = std::min(target, room / u);
    v_floor = std::min(v_floor, quadratic_speed_mm_s(0.0, du / derived_.dt_s, derived_.axis_accel_mm_s2[i] - floor * u));
  }
  if (feasible && target >= floor) return target;
  // The corner is slower than the feed whatever the split. A line shorter
  // than the way from that corner speed up to the feed never reaches its
  // feed: the corner speed rules, and gets all but the floor share. A longer
  // one spends its time at the feed: it keeps its full rate.
  return g.length_mm < (v * v - v_floor * v_floor) / (2.0 * full) ? floor : full;
}

double SegmentQueue::speed_up_accel_mm_s2(const QueuedSegment& q, double speed_mm_s) const noexcept {
  const SegmentGeometry& g = q.geometry;
  const double k = curvature_per_mm(g);
  if (k <= 0.0) return std::max(q.tangent_accel_mm_s2, line_accel_mm_s2(derived_, g.unit_start));
  const double a = std::min(kTangentShare * arc_axis_accel_mm_s2(derived_), derived_.path_accel_cap_mm_s2);
  const double v = speed_mm_s + a * derived_.dt_s;  // the centripetal term at the speed it reaches
  const double c = k * v * v;
  return c < a ? std::max(q.tangent_accel_mm_s2, std::sqrt(a * a - c * c)) : q.tangent_accel_mm_s2;
}

// The tick that crosses a corner (and the one after it) moves the path
// point's velocity from v u_a to v u_b: per axis the second difference gains
// v |u_b - u_a|_i dt, on top of the tangential change (the element's
// tangent_accel along its tangent) and an arc's centripetal v^2/r along its
// normal (|n_i| <= sqrt(1 - u_i^2)). Each axis keeps the sum within its own
// limit. The moving average then rounds the corner; with the path speed v
// at the corner the rounded path stays within v sin(theta) T / 8 of the
// corner's two sides (T = taps * dt; docs/motion.md).
double SegmentQueue::corner_limit_mm_s(const QueuedSegment& before, const QueuedSegment& after) const noexcept {
  const PlanePoint& ua = before.geometry.unit_end;
  const PlanePoint& ub = after.geometry.unit_start;
  const double dt = derived_.dt_s;
  const double ka = curvature_per_mm(before.geometry);
  const double kb = curvature_per_mm(after.geometry);
  double v = kUnlimited_mm_s;
  double du2 = 0.0;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const double du = std::fabs(ub[i] - ua[i]);
    du2 += du * du;
    const double tangential = std::max(before.tangent_accel_mm_s2 * std::fabs(ua[i]),
                                       after.tangent_accel_mm_s2 * std::fabs(ub[i]));
    const double normal = std::max(ka * std::sqrt(std::max(0.0, 1.0 - ua[i] * ua[i])),
                                   kb * std::sqrt(std::max(0.0, 1.0 - ub[i] * ub[i])));
    v = std::min(v, quadratic_speed_mm_s(normal, du / dt, derived_.axis_accel_mm_s2[i] - tangential));
  }
  // |u_b - u_a| = 2 sin(theta / 2): sin(theta) without x/y cross products.
  const double du_norm = std::sqrt(du2);
  const double sin_turn = du_norm * std::sqrt(std::max(0.0, 1.0 - 0.25 * du2));
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
  // A probe starts at rest (its input is checked there): the element before
  // it ends at rest, by the same reasoning.
  if (!empty() && is_feed_move(segment)) {
    QueuedSegment& rapid_before = at(tail_seq_ - 1);
    if ((rapid_before.segment.rapid || segment.probe != ProbeKind::none) &&
        rapid_before.segment.kind != SegmentKind::dwell)
      rapid_before.segment.exact_stop = true;
  }
  const QueuedSegment* before = nullptr;
  if (!empty() && segment.kind != SegmentKind::dwell && !segment.profiled()) {
    const QueuedSegment& b = at(tail_seq_ - 1);
    if (b.segment.kind != SegmentKind::dwell && !b.segment.exact_stop && !b.segment.profiled()) before = &b;
  }
  // A dwell's is never used; keep it positive all the same.
  q.tangent_accel_mm_s2 = segment.kind == SegmentKind::dwell ? derived_.path_accel_mm_s2 : tangent_accel_mm_s2(q, before);
  if (before != nullptr) q.entry_limit_mm_s = corner_limit_mm_s(*before, q);
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
