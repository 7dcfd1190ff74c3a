#pragma once
// TickTask's input shapers (design notes "Input shaping"): each axis'
// design and on/off, and the one series every axis of the path runs
// (path_taps.hpp), so shaped axes stay in step. A change is planned when
// asked (refused, changing nothing, when the series does not fit) and
// handed to every axis' StreamShaper in the same tick, once all of them
// are quiet (or the servo is off), so it never makes a jump. With no
// shaper on, the reference passes through untouched, bit for bit.
//
// Bounded work, no allocation, exceptions, locks or logging: shape() and
// forward_when_quiet() run in the 1 ms tick.
#include <array>
#include <cstddef>

#include "firmware/shaper/path_taps.hpp"
#include "firmware/shaper/shaper_design.hpp"
#include "firmware/shaper/stream_shaper.hpp"
#include "firmware/trajectory/plane_reference.hpp"
#include "hal/axis.hpp"

namespace tnv::fw {

class PathShapers {
 public:
  // Axis a's design (checked by the task: a valid spec on the tick's grid):
  // false, nothing changed, when the path's series would not fit.
  bool configure(std::size_t a, const ShaperDesign& design) noexcept;
  // Axis a's own shaper on or off: false, nothing changed, when it was never
  // configured (on) or the series would not fit.
  bool enable(std::size_t a, bool on) noexcept;
  // In the tick: a planned series goes to every axis once all are quiet or `servo_off`.
  void forward_when_quiet(bool servo_off) noexcept;

  // The reference pair the controllers get: the source's x_k and x_{k+1}
  // through axis i's shaper, y_k (its previous output) and y_{k+1}; or the
  // source's own, bit for bit, while the shaper is off.
  struct Pair {
    AxisSample now;
    AxisSample next;
  };
  Pair shape(std::size_t i, const AxisSample& now, const AxisSample& next) noexcept;
  // Every shaping axis' stream has come to rest.
  bool settled() const noexcept;
  // Axis i's shaper rests at `rest` (the reference jumped there: hold, a new frame).
  void reset(std::size_t i, const AxisSample& rest) noexcept { axis_[i].shaper.reset(rest); }

  const StreamShaper& shaper(std::size_t i) const noexcept { return axis_[i].shaper; }
  const ShaperDesign& design(std::size_t i) const noexcept { return axis_[i].design; }
  // Axis i's own shaper is on and the path shaper that includes it is active.
  bool active(std::size_t i) const noexcept { return axis_[i].enabled && axis_[i].shaper.shaping(); }

 private:
  struct AxisShaping {
    StreamShaper shaper{};
    ShaperDesign design{};
    bool configured = false;
    bool enabled = false;  // this axis' own shaper is on (the path runs all of them)
  };
  // The series for `axes`, to be handed over once every axis is quiet.
  bool plan(const std::array<AxisShaperChoice, hal::kAxisCount>& axes) noexcept;

  std::array<AxisShaping, hal::kAxisCount> axis_{};  // the ring buffers are large
  TapSet path_taps_ = TapSet::identity();
  bool path_shaping_ = false;
  bool change_pending_ = false;
};

}  // namespace tnv::fw
