#pragma once
// TickTask's excitations (issue 7 identification, issue 17 frequency
// response; firmware/compensation/excitation.hpp): one generator per axis
// and the encoder count it started at. An open-loop excitation gives the
// axis' speed command instead of its controller, its hold point following
// the table; a sweep or multisine (closed loop) is added to the
// controller's command, the controller holding the axis, on a carrier
// moving the hold point through the drive phase. The task decides when one
// may start (holding, none running) and steps it in the tick: the hold
// point at the reference step (hold_step()), the command at the control
// step (next()).
//
// Bounded work, no allocation, exceptions, locks or logging: hold_step()
// and next() run in the 1 ms tick; start() between ticks.
#include <array>
#include <cstddef>
#include <cstdint>

#include "firmware/compensation/excitation.hpp"
#include "firmware/supervisor/supervisor.hpp"
#include "hal/axis.hpp"

namespace tnv::fw {

class AxisExcitations {
 public:
  // Axis a's excitation from now, the axis' encoder at `counts` (spec
  // validated and the start allowed by the task).
  void start(std::size_t a, const ExcitationSpec& spec, std::int64_t counts) noexcept {
    start_counts_[a] = counts;
    generator_[a].start(spec);
  }
  bool running() const noexcept {  // on any axis
    for (const ExcitationGenerator& g : generator_)
      if (g.active()) return true;
    return false;
  }
  bool running(std::size_t a) const noexcept { return generator_[a].active(); }
  // Running and open loop: its command replaces the controller's.
  bool open_loop(std::size_t a) const noexcept { return generator_[a].active() && !generator_[a].closed_loop(); }

  // What a running excitation does to axis a's hold point this tick.
  struct HoldStep {
    enum class Kind : std::uint8_t {
      none,          // nothing (none running, cancelled, or closed loop at rest)
      carrier,       // closed loop on a carrier: the hold point moves at speed_mm_s
      follow_table,  // open loop: the hold point follows the measured position
    };
    Kind kind = Kind::none;
    double speed_mm_s = 0.0;
  };
  // The tick's reference step. Outside holding (`holding` false: a motion,
  // disable or a fault) a running excitation is cancelled.
  HoldStep hold_step(std::size_t a, bool holding) noexcept {
    ExcitationGenerator& g = generator_[a];
    if (!g.active()) return {};
    if (!holding) {
      g = ExcitationGenerator{};
      return {};
    }
    if (!g.closed_loop()) return {HoldStep::Kind::follow_table, 0.0};
    if (g.has_carrier()) return {HoldStep::Kind::carrier, g.carrier_mm_s()};
    return {};
  }
  // The tick's control step: the excitation's command, axis a's encoder at
  // `counts` (the generator may end with it: running(a) false after).
  double next(std::size_t a, std::int64_t counts) noexcept { return generator_[a].next(counts - start_counts_[a]); }

  // The carrier's travel (carrier x duration from standing_mm) ends inside
  // `limits` (always, without a carrier).
  static bool carrier_travel_fits(const AxisLimits& limits, double standing_mm, const ExcitationSpec& spec) noexcept {
    if (spec.carrier_mm_s == 0.0) return true;
    const double end_mm = standing_mm + spec.carrier_mm_s * spec.duration_s;
    return end_mm >= limits.position_min_mm && end_mm <= limits.position_max_mm;
  }

 private:
  std::array<ExcitationGenerator, hal::kAxisCount> generator_{};
  std::array<std::int64_t, hal::kAxisCount> start_counts_{};
};

}  // namespace tnv::fw
