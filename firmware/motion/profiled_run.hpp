#pragma once
// Runs one profiled element (Segment::ramp_s > 0): a line or arc whose path
// distance follows the S1 protocol's time law, raised-cosine feed ramps at
// start and end (trajectory/feed_profile.hpp), from rest to rest. The
// reference at k and k+1 comes from the time law itself, position and
// speed, with no filter and no delay: the circle experiment of the
// reference plant ("Circle experiment") and the point-to-point move run
// here. A controlled stop warps time: its rate falls from 1 to 0 along a
// raised cosine over the element's own ramp time, so the reference
// decelerates along the path and rests where it stops.
#include <cstdint>

#include "firmware/control/axis_controller.hpp"
#include "firmware/motion/segment_geometry.hpp"
#include "firmware/trajectory/feed_profile.hpp"

namespace tnv::fw::motion {

struct PathSample {
  PlanePoint position_mm{};
  PlanePoint speed_mm_s{};
};

struct ProfiledStep {
  std::array<AxisReference, hal::kAxisCount> axis{};  // x_ref,k and x_ref,k+1
  double path_speed_mm_s = 0.0;
  bool done = false;  // this was the element's last tick; it rests at the end of it (or where it stopped)
};

class ProfiledRun {
 public:
  // Requires g prepared from a profiled segment (prepare() accepted it).
  void start(const SegmentGeometry& g, double feed_mm_s, double ramp_s, double period_s) noexcept;
  ProfiledStep step() noexcept;
  // Controlled stop (see above); nothing when already stopping or idle.
  void stop() noexcept;

  bool active() const noexcept { return active_; }
  bool stopping() const noexcept { return stop_.active; }
  // Ticks from the first to the last moving tick of the unstopped element.
  std::int64_t motion_ticks() const noexcept { return motion_ticks_; }
  // Where the element rests once done.
  const PlanePoint& rest_mm() const noexcept { return rest_mm_; }

  // The time law's sample t_s after the start.
  PathSample at(double t_s) const noexcept;

 private:
  struct StopWarp {  // tau advances by rate x T per tick, rate_k = (1 + cos(pi k / n)) / 2
    bool active = false;
    std::int64_t k = 0;
    std::int64_t n = 1;
    double tau_s = 0.0;
  };
  PathSample point_at(double distance_mm, double speed_mm_s) const noexcept;

  SegmentGeometry geometry_{};
  FeedProfile profile_{};
  double ramp_s_ = 0.0;
  double period_s_ = 1e-3;
  std::int64_t tick_ = 0;
  std::int64_t motion_ticks_ = 0;
  StopWarp stop_{};
  PlanePoint rest_mm_{};
  bool active_ = false;
  // x_{k+1} as computed at tick k: tick k+1's x_k, the same call with the
  // same argument, so it is taken instead of computed twice. -1: none.
  std::int64_t next_sample_tick_ = -1;
  PathSample next_sample_{};
};

}  // namespace tnv::fw::motion
