#pragma once
// Open-loop excitation of one axis for plant identification (issue 7,
// item 1): the tick task drives the axis' speed command from this
// generator instead of its controller, while the capture records what the
// axis does. Fixed cost per tick, no allocation.
//
//   step: u = level for duration_s, then 0 for settle_s (the speed loop's
//         step response, then the coast to rest).
//   ramp: u = sign(level) * rate * t, |u| <= |level|, until the axis has
//         moved breakaway_counts encoder counts (stiction broken) or
//         duration_s is over; then 0 for settle_s. The command at the
//         first moving tick is the breakaway level f_s / K.
#include <cstdint>

#include "firmware/control/param_check.hpp"

namespace tnv::fw {

enum class ExcitationKind : std::uint8_t { step = 0, ramp = 1 };

struct ExcitationSpec {
  ExcitationKind kind = ExcitationKind::step;
  double level_mm_s = 10.0;      // step level, or the ramp's sign and largest |u|
  double rate_mm_s2 = 2.0;       // ramp only, > 0
  double duration_s = 0.15;      // step length / longest ramp
  double settle_s = 0.2;         // u = 0 after, the axis comes to rest
  std::int32_t breakaway_counts = 12;  // ramp only: counts moved that end the ramp
};

// Finite; 0 < |level| <= 100 mm/s; 0.001 <= duration_s <= 10;
// 0 <= settle_s <= 10; ramp: 0 < rate <= 1000, 1 <= breakaway_counts <= 10000.
ParamCheck validate(const ExcitationSpec& spec) noexcept;

class ExcitationGenerator {
 public:
  void start(const ExcitationSpec& spec) noexcept;
  // The command for this tick, from the counts moved since start().
  double next(std::int64_t counts_moved) noexcept;
  bool active() const noexcept { return active_; }
  // Tick index (from 0) at which the ramp saw the axis move; -1 if not (yet).
  std::int64_t breakaway_tick() const noexcept { return breakaway_tick_; }

 private:
  ExcitationSpec spec_{};
  bool active_ = false;
  std::int64_t k_ = 0;
  std::int64_t drive_ticks_ = 0;
  std::int64_t settle_ticks_ = 0;
  std::int64_t stop_tick_ = -1;  // the tick the drive phase ended
  std::int64_t breakaway_tick_ = -1;
};

}  // namespace tnv::fw
