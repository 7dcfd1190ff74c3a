#pragma once
// The operator's jog as a producer of segments. A pendant held down sends
// target speeds per axis; while the stream is fresh the producer keeps a
// short stretch of straight line queued ahead of the path point (its
// braking distance plus two pieces of 20 ms), in the direction of the
// target speed vector. The pieces carry the fastest feed that direction
// allows and the feed override sets the jog speed, so a new speed takes
// effect at once, at the path's acceleration, with its jerk-limited
// S-curve; the queue end is never closer than a stop. A zero target, a stop, or the dead man (no command for
// deadman_s on a moving axis) ends it as a controlled stop on the path. A
// change of direction goes through rest: brake, then start the new line.
// The line is clipped to the soft limits, so a jog rests on them.
#include <array>
#include <cstdint>

#include "firmware/motion/motion_interpolator.hpp"
#include "firmware/trajectory/jog_limits.hpp"

namespace tnv::fw::motion {

class JogProducer {
 public:
  // At rest, no target, dead-man timers cleared; `limits` per axis.
  void start(const std::array<JogLimits, hal::kAxisCount>& limits) noexcept;
  // The operator's target speed for one axis; refreshes its dead man.
  // False (nothing changes) when not finite or beyond its speed limit.
  bool command(std::size_t axis, double speed_mm_s) noexcept;
  // Every target to 0 (a controlled stop of the jog).
  void release() noexcept;

  // Once per tick, before the interpolator's tick: the dead man, then the
  // path (stop, restart in a new direction, or top up the queued line).
  void produce(MotionInterpolator& motion) noexcept;

  // Nothing to do and nothing queued: the jog is over once the interpolator rests.
  bool idle() const noexcept { return !feeding_ && target_speed_mm_s() == 0.0; }
  double target_mm_s(std::size_t axis) const noexcept { return target_mm_s_[axis]; }
  std::uint32_t deadman_stops() const noexcept { return deadman_stops_; }

 private:
  double target_speed_mm_s() const noexcept;
  void top_up(MotionInterpolator& motion) noexcept;

  std::array<JogLimits, hal::kAxisCount> limits_{};
  std::array<double, hal::kAxisCount> target_mm_s_{};
  std::array<double, hal::kAxisCount> silence_s_{};
  PlanePoint direction_{};  // unit vector of the line being fed
  double line_feed_mm_s_ = 0.0;  // the pieces' feed: the fastest the direction allows
  bool feeding_ = false;    // segments are being queued
  std::uint32_t deadman_stops_ = 0;
};

}  // namespace tnv::fw::motion
