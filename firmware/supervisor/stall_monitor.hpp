#pragma once
// Stall monitor: the encoder count has not changed for `ticks` ticks in a
// row while the command that acted over each of those ticks (the previous
// tick's output) was at least `command_mm_s` in magnitude. A table driven
// that hard moves several counts per tick, so either the encoder is dead
// (its count register froze) or the axis is jammed; both are faults, and
// the following error alone finds a dead encoder only after the blind loop
// has driven the table millimetres away (docs/safety.md).
//
// The level must sit above the command that breaks the axis away from
// stiction (f_s / K), or a slow breakaway would count as a stall.
#include <cmath>
#include <cstdint>

namespace tnv::fw {

struct StallLimit {
  double command_mm_s = 8.0;  // |u| at or above this counts; reference plant breaks away at 3 mm/s
  std::uint32_t ticks = 4;    // consecutive ticks without a count that trip
  bool operator==(const StallLimit&) const = default;
};

class StallMonitor {
 public:
  // One tick: this tick's encoder count, the command that acted since the
  // previous tick, and whether the outputs were live over it. Returns the
  // number of consecutive stalled ticks so far (0 when the axis moved).
  std::uint32_t update(std::int64_t counts, double applied_command_mm_s, bool applied_live,
                       const StallLimit& limit) noexcept {
    const bool moved = !primed_ || counts != last_counts_;
    primed_ = true;
    last_counts_ = counts;
    applied_command_mm_s_ = applied_command_mm_s;
    const bool driven = applied_live && std::fabs(applied_command_mm_s) >= limit.command_mm_s;
    stalled_ticks_ = (!moved && driven) ? stalled_ticks_ + 1 : 0;
    return stalled_ticks_;
  }
  std::uint32_t stalled_ticks() const noexcept { return stalled_ticks_; }
  // The command of the last update (what the fault record reports).
  double applied_command_mm_s() const noexcept { return applied_command_mm_s_; }
  void reset() noexcept { *this = StallMonitor{}; }

 private:
  bool primed_ = false;
  std::int64_t last_counts_ = 0;
  double applied_command_mm_s_ = 0.0;
  std::uint32_t stalled_ticks_ = 0;
};

}  // namespace tnv::fw
