#pragma once
// TickTask's homing state (COMMAND home, docs/safety.md "Homing"): the
// axes one HOME command names, homed one after the other in
// hal::kHomingOrder, each by its own HomingCycle; and what homing left per
// axis (homed, the last cycle's result). The task owns one and asks it for
// the homing axis' reference step each tick; the frame shift at the index
// and the end of the motion stay the task's (they touch its reference).
//
// Bounded work, no allocation, exceptions, locks or logging: it runs in the
// 1 ms tick.
#include <array>
#include <cstddef>
#include <cstdint>

#include "firmware/homing/homing_cycle.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/trajectory/plane_reference.hpp"
#include "hal/axis.hpp"

namespace tnv::fw {

class HomingSequence {
 public:
  using HoldPoints = std::array<AxisSample, hal::kAxisCount>;

  // Queues `axes` (non-empty, of the machine: the task checked) and starts
  // the first in hal::kHomingOrder from its hold point.
  void begin(hal::AxisSet axes, const FirmwareConfig& config, const HoldPoints& hold, double tick_s) noexcept;
  // The homing axis' reference this tick, from the snapshot's switch and index edges.
  HomingStep step(bool home_switch, std::uint8_t index_edges) noexcept { return cycle_.step(home_switch, index_edges); }
  // The homing axis' frame moved by delta_mm (at the index): the cycle moves with it.
  void shift(double delta_mm) noexcept { cycle_.shift(delta_mm); }
  // The homing axis' cycle has ended (not running()): its result is
  // recorded and, when it homed, the next queued axis starts from its hold
  // point (true). false: the command is over; finish() it.
  bool next_axis(const FirmwareConfig& config, const HoldPoints& hold, double tick_s) noexcept;
  // The command is over: the last cycle (failed or done), the queue emptied.
  HomingCycle finish() noexcept;
  // stop(): the running cycle brakes to rest, then ends aborted (not homed).
  void abort() noexcept { cycle_.abort(); }
  // Cut short (servo off, a fault): a running cycle ends aborted, the queue is emptied.
  void cancel() noexcept;

  bool running() const noexcept { return cycle_.running(); }
  std::size_t axis() const noexcept { return axis_; }  // the homing axis, while running()
  // Soft limits are off for the axis that homes now.
  bool soft_limits_off(std::size_t a) const noexcept { return running() && axis_ == a; }
  bool homed(std::size_t a) const noexcept { return homed_[a]; }
  HomingResult result(std::size_t a) const noexcept { return result_[a]; }
  // The axis' frame is no longer the index's (zero(), an untrusted count).
  void unhome(std::size_t a) noexcept { homed_[a] = false; }
  void unhome_all() noexcept { homed_ = {}; }

 private:
  // The queued axis that homes after `after` (hal::kHomingOrder); kAxisCount
  // for none. after = kAxisCount: the first.
  std::size_t next_queued(std::size_t after) const noexcept;
  void start(std::size_t a, const FirmwareConfig& config, const HoldPoints& hold, double tick_s) noexcept;

  HomingCycle cycle_{};
  std::size_t axis_ = 0;
  std::array<bool, hal::kAxisCount> queued_{};  // axes still to home in this command
  std::array<bool, hal::kAxisCount> homed_{};
  std::array<HomingResult, hal::kAxisCount> result_{};
};

}  // namespace tnv::fw
