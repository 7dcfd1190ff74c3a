#pragma once
// One axis' homing cycle (docs/safety.md "Homing"), stepped once per tick
// with bounded work: search for the home switch at the search speed, stop,
// back off at the latch speed until the switch releases, carry on at the
// latch speed to the next encoder index edge. The count the board latched
// at that edge is home: the tick task moves the axis' frame so that count
// reads HomingParams::position_mm, then the cycle brakes to rest.
//
// The cycle makes the axis' reference (position and speed, accelerating at
// a fixed rate toward each phase's target speed); it reads the switch and
// the index edge counter of the tick's snapshot. Every phase is bounded in
// travel (search_max_mm, latch_max_mm), and the reference always moves at
// its phase's speed, so the whole cycle is bounded in time too. A phase that
// runs out of travel brakes to rest and ends failed with its reason.
#include <cstdint>

#include "firmware/control/param_check.hpp"
#include "hal/axis.hpp"

namespace tnv::fw {

struct HomingParams {
  bool search_positive = false;  // the switch is at the positive end of the travel
  double search_mm_s = 10.0;     // toward the switch
  double latch_mm_s = 1.0;       // off the switch and on to the index
  double position_mm = 0.0;      // machine position given to the index mark home is taken at
  double search_max_mm = 400.0;  // the longest search without finding the switch (the axis' travel)
  double latch_max_mm = 25.0;    // the longest back-off, and the longest run from release to an index
  bool operator==(const HomingParams&) const = default;
};

// The TNV-40's switches: X's and Y's at the negative end of the table's
// travel, Z's at the top of the head's (reference plant "Z axis"). One case
// per axis and no default: a new axis of TNV_AXES fails the build
// (-Wswitch) until its switch side is stated here.
HomingParams machine_homing_params(hal::Axis axis) noexcept;

// Checks: speeds > 0 and finite, latch speed <= search speed, travels > 0, position finite.
ParamCheck validate(const HomingParams& p) noexcept;

enum class HomingPhase : std::uint8_t { idle, search, search_stop, back_off, find_index, final_stop, failing_stop, done, failed };

// How the last cycle of an axis ended (kept until the next one starts).
enum class HomingResult : std::uint8_t {
  none = 0,             // never homed since power-up
  running,              // a cycle runs
  homed,                // home set at the index after the switch
  switch_not_found,     // search_max_mm travelled without the switch
  switch_not_released,  // latch_max_mm backed off and the switch still on
  index_not_found,      // latch_max_mm past the release without an index edge
  aborted,              // stopped, disabled or faulted before the end
};

constexpr const char* to_string(HomingResult r) noexcept {
  switch (r) {
    case HomingResult::none: return "none";
    case HomingResult::running: return "running";
    case HomingResult::homed: return "homed";
    case HomingResult::switch_not_found: return "switch_not_found";
    case HomingResult::switch_not_released: return "switch_not_released";
    case HomingResult::index_not_found: return "index_not_found";
    case HomingResult::aborted: return "aborted";
  }
  return "?";
}

struct HomingSample {
  double position_mm = 0.0;
  double speed_mm_s = 0.0;
};

// One tick of the cycle: the reference x_k and x_{k+1}, and whether the
// index edge that defines home latched in this tick's snapshot.
struct HomingStep {
  HomingSample now;
  HomingSample next;
  bool index_found = false;
};

class HomingCycle {
 public:
  // From rest at position_mm (the current frame); accel_mm_s2 > 0, tick_s > 0.
  void start(const HomingParams& params, double accel_mm_s2, double position_mm, double tick_s) noexcept;
  HomingStep step(bool switch_on, std::uint8_t index_edges) noexcept;
  // Brake to rest and end as aborted.
  void abort() noexcept;
  // The frame moved by delta_mm (home found): the reference moves with it.
  void shift(double delta_mm) noexcept { position_mm_ += delta_mm; }

  HomingPhase phase() const noexcept { return phase_; }
  bool running() const noexcept { return phase_ != HomingPhase::idle && phase_ != HomingPhase::done && phase_ != HomingPhase::failed; }
  // Set when the cycle ends (done: homed; failed: the reason).
  HomingResult result() const noexcept { return result_; }
  // For a failure: how far the failing phase ran, and its bound.
  double failed_travel_mm() const noexcept { return failed_travel_mm_; }
  double failed_limit_mm() const noexcept { return failed_limit_mm_; }

 private:
  void fail(HomingResult why, double travel_mm, double limit_mm) noexcept;

  HomingParams params_{};
  double accel_mm_s2_ = 1.0;
  double tick_s_ = 1e-3;
  double position_mm_ = 0.0;
  double speed_mm_s_ = 0.0;
  double target_mm_s_ = 0.0;
  double phase_start_mm_ = 0.0;
  std::uint8_t edges_at_release_ = 0;
  HomingPhase phase_ = HomingPhase::idle;
  HomingResult result_ = HomingResult::none;
  HomingResult pending_ = HomingResult::none;
  double failed_travel_mm_ = 0.0;
  double failed_limit_mm_ = 0.0;
};

}  // namespace tnv::fw
