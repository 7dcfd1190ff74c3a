#pragma once
// The operator's jog: a live stream of target speeds (a pendant held down
// keeps sending them) turned into a reference, one sample per tick. The
// speed moves toward the target at a bounded acceleration; position is
// the exact integral of that piecewise-linear speed. Dead man: when no
// command has arrived for deadman_s, the target falls to zero and the
// axis brakes to a stop by itself. Unbounded in length; fixed state.
#include <cstdint>

#include "firmware/control/param_check.hpp"
#include "firmware/trajectory/plane_reference.hpp"

namespace tnv::fw {

struct JogLimits {
  double speed_max_mm_s = 50.0;
  double accel_mm_s2 = 1000.0;
  double deadman_s = 0.1;  // longest silence of the operator stream before it stops the axis
};

// Checks: all finite and > 0.
ParamCheck validate(const JogLimits& limits) noexcept;

class JogStream {
 public:
  JogStream() = default;
  explicit JogStream(const JogLimits& limits) noexcept : limits_(limits) {}

  // At rest at position_mm, no target, dead-man timer cleared.
  void start(double position_mm) noexcept;
  // The operator's target speed; refreshes the dead man. False (nothing
  // changes) when non-finite or beyond the speed limit.
  bool command(double speed_mm_s) noexcept;
  // Advances one period and returns the new sample (x_{k+1}).
  AxisSample advance(double period_s) noexcept;

  const AxisSample& current() const noexcept { return now_; }
  double target_mm_s() const noexcept { return target_mm_s_; }
  bool at_rest() const noexcept { return now_.speed_mm_s == 0.0 && target_mm_s_ == 0.0; }
  std::uint32_t deadman_stops() const noexcept { return deadman_stops_; }

 private:
  JogLimits limits_{};
  AxisSample now_{};
  double target_mm_s_ = 0.0;
  double silence_s_ = 0.0;
  std::uint32_t deadman_stops_ = 0;
};

}  // namespace tnv::fw
