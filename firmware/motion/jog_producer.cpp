#include "firmware/motion/jog_producer.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::fw::motion {

namespace {

constexpr double kPieceS = 0.02;           // one queued piece of line: 20 ms at the jog speed
constexpr double kSameDirection = 1e-9;    // |cross product| of unit vectors: same line
constexpr double kLimitMarginMm = 1e-6;    // the line ends this far inside the soft limits

}  // namespace

void JogProducer::start(const std::array<JogLimits, hal::kAxisCount>& limits) noexcept {
  limits_ = limits;
  target_mm_s_ = {};
  silence_s_ = {};
  direction_ = {};
  feeding_ = false;
}

bool JogProducer::command(std::size_t axis, double speed_mm_s) noexcept {
  if (axis >= hal::kAxisCount) return false;
  if (!std::isfinite(speed_mm_s) || std::fabs(speed_mm_s) > limits_[axis].speed_max_mm_s) return false;
  target_mm_s_[axis] = speed_mm_s;
  silence_s_[axis] = 0.0;
  return true;
}

void JogProducer::release() noexcept { target_mm_s_ = {}; }

double JogProducer::target_speed_mm_s() const noexcept {
  double speed = std::hypot(target_mm_s_[0], target_mm_s_[1]);
  for (std::size_t i = 2; i < hal::kAxisCount; ++i) speed = std::hypot(speed, target_mm_s_[i]);
  return speed;
}

void JogProducer::produce(MotionInterpolator& motion) noexcept {
  const double dt = motion.derived().dt_s;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    silence_s_[i] += dt;
    if (silence_s_[i] > limits_[i].deadman_s && target_mm_s_[i] != 0.0) {
      target_mm_s_[i] = 0.0;  // the operator went quiet: stop
      ++deadman_stops_;
    }
  }
  const double speed = target_speed_mm_s();
  if (speed == 0.0) {
    if (feeding_) {
      motion.stop();  // brake on the path, drop what is queued
      motion.end_program();
      feeding_ = false;
    }
    return;
  }
  PlanePoint dir{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) dir[i] = target_mm_s_[i] / speed;
  if (feeding_) {
    // |direction x dir| over every pair of axes (the plane's alone with two).
    double cross_sq = 0.0, dot = 0.0;
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      dot += direction_[i] * dir[i];
      for (std::size_t j = i + 1; j < hal::kAxisCount; ++j) {
        const double c = direction_[i] * dir[j] - direction_[j] * dir[i];
        cross_sq += c * c;
      }
    }
    if (std::sqrt(cross_sq) > kSameDirection || dot <= 0.0) {
      motion.stop();  // a new direction goes through rest
      motion.end_program();
      feeding_ = false;
      return;
    }
  } else {
    if (!motion.at_rest() || motion.state() == MotionState::stopping) return;  // the last stop is still braking
    direction_ = dir;
    line_feed_mm_s_ = 0.0;
    const MotionLimits& lim = motion.limits();
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      const double u = std::fabs(dir[i]);
      if (u < 1e-12) continue;
      const double cap = std::min(limits_[i].speed_max_mm_s, lim.axis[i].speed_mm_s) / u;
      line_feed_mm_s_ = line_feed_mm_s_ == 0.0 ? cap : std::min(line_feed_mm_s_, cap);
    }
    feeding_ = true;
  }
  (void)motion.set_feed_override(std::min(speed / line_feed_mm_s_, 1.0));
  top_up(motion);
}

// Queue pieces of the line until the path ahead covers a stop from the
// pieces' feed (the planner never runs faster than it can stop at the
// queue end) plus two pieces, so the jog cruises at any override.
void JogProducer::top_up(MotionInterpolator& motion) noexcept {
  const double speed = line_feed_mm_s_;
  const DerivedLimits& d = motion.derived();
  const double window_s = static_cast<double>(d.filter_taps) * d.dt_s;
  const double piece_mm = std::max(speed * kPieceS, 3.0 * speed * d.dt_s);
  const double lead_mm = speed * speed / (2.0 * d.path_accel_mm_s2) + speed * window_s + 2.0 * piece_mm;
  const MotionLimits& lim = motion.limits();
  while (motion.queued_path_mm() < lead_mm && motion.free_slots() > 1) {
    const PlanePoint& from = motion.queue_end_mm();
    double length = piece_mm;
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      // Clip the piece to the soft limits along the line.
      if (direction_[i] > 0.0)
        length = std::min(length, (lim.axis[i].position_max_mm - kLimitMarginMm - from[i]) / direction_[i]);
      else if (direction_[i] < 0.0)
        length = std::min(length, (lim.axis[i].position_min_mm + kLimitMarginMm - from[i]) / direction_[i]);
    }
    if (!(length >= lim.min_segment_mm)) break;  // at the soft limit: the jog rests there
    PlanePoint to{};
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) to[i] = from[i] + direction_[i] * length;
    if (motion.push(line_to(to, line_feed_mm_s_)) != SegmentRefusal::none) break;
  }
}

}  // namespace tnv::fw::motion
