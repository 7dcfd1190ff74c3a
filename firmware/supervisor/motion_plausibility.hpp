#pragma once
// Motion plausibility: does the encoder count move the way the axis model
// says the applied commands can move the table?
//
// With the model x_{k+1} = A x_k + B (u_k + d_k) (A11 = 1, A21 = 0, as every
// AxisModel here: axis_model.hpp) the speed state eliminates to an exact
// relation between measured position steps dp_k = p_k - p_{k-1} and the
// commands the DAC applied:
//   dp_k = A22 dp_{k-1} + B1 w_{k-1} + C w_{k-2},  C = A12 B2 - A22 B1,  w = u + d
// so the residual r_k = dp_k - (A22 dp_{k-1} + B1 u_{k-1} + C u_{k-2}) is what
// the commands do not explain (friction, cutting, model error: d).
//
// Two checks use it (docs/safety.md):
// - count jump (1 tick): dp_k outside what any disturbance up to the DAC's
//   whole command range could give, widened to include 0 (a jammed table may
//   stop dead; it cannot jump) and by kQuantisationCounts -> encoder_implausible.
// - runaway (kRunawayWindowTicks ticks): every command applied over the
//   window points one way (and is at least runaway_min_command_mm_s), this
//   tick's step points the other way, and the step grew the other way over
//   the window by more than the quantisation plus runaway_margin_mm_s:
//   the table speeds up against its command. Friction opposes the motion,
//   so it cannot do that; a frozen count or a jam stops the table (a step of
//   0 is never against); a plant slower or faster than the model changes
//   how fast the table follows, not which way. Only a drive that pushes the
//   wrong way (or a disturbance larger than the command) does it.
// - runaway at speed (1 tick), while the table still moves the commanded
//   way: the input that explains this tick's step,
//   w = (dp_k - A22 dp_{k-1}) / (B1 + C) (the relation with w held over both
//   intervals), points against a command of at least
//   runaway_push_min_command_mm_s (both commands of the relation and dp_k
//   one way) by more than runaway_push_fraction of it plus the
//   quantisation. A moving table's step shrinks as it brakes, long before
//   it turns; this sees the brake. A drive of any gain and time constant
//   near the model's pushes the table with its command (w ~ K u + (tau -
//   tau') a), friction and cutting are a fraction of it; a flipped drive
//   gives w ~ -K u. A stop dead (jam, frozen count) gives
//   w ~ -A22/(1 - A22) v, about -5 v, beyond any drive's push: not a
//   runaway (stall monitor).
#include <array>
#include <cstdint>

#include "firmware/control/axis_model.hpp"

namespace tnv::fw {

struct PlausibilityLimit {
  // A disturbance (as a speed command) the table can meet, as a multiple of
  // the DAC's full-scale speed: 1 = as large as the whole command range.
  double jump_disturbance_scale = 1.0;
  // Speed gained against the command over the window beyond the quantisation.
  double runaway_margin_mm_s = 0.25;
  // Commands below this (hunting at standstill) are not a direction.
  double runaway_min_command_mm_s = 2.0;
  // Commands below this are not checked by the 1-tick push check (lag and
  // friction terms are not small against them).
  double runaway_push_min_command_mm_s = 10.0;
  // w against the command beyond this fraction of |u| (and the quantisation)
  // is a runaway; a healthy drive gives w ~ +K u.
  double runaway_push_fraction = 0.25;
  bool operator==(const PlausibilityLimit&) const = default;
};

struct PlausibilityVerdict {
  bool checked = false;       // the history was primed (consecutive good ticks)
  bool jump = false;          // dp outside the reachable interval
  bool runaway = false;       // speeding up against the command beyond the margin
  double step_mm = 0.0;       // dp_k
  double predicted_mm = 0.0;  // A22 dp_{k-1} + B1 u_{k-1} + C u_{k-2}
  double spread_mm = 0.0;     // half-width of the reachable interval
  double against_mm = 0.0;    // -s (dp_k - dp_{k-N}): step gained against the command (> 0 = against)
  double against_limit_mm = 0.0;
  bool runaway_push = false;       // the step's input w points against the command (1-tick check)
  double push_against_mm_s = 0.0;  // -s w: input against the command (> 0 = against)
  double push_limit_mm_s = 0.0;
};

class MotionPlausibility {
 public:
  static constexpr std::int64_t kQuantisationCounts = 3;  // the residual's floor errors reach +-1.83 counts
  static constexpr std::size_t kRunawayWindowTicks = 2;
  static constexpr double kRunawayPushGainMax = 2.0;  // a flipped drive's |w| / |u| at most

  // One tick. `counts`: this snapshot's count; `applied_mm_s`: the command
  // the DAC applied over the interval this snapshot ends (0 if the outputs
  // were off); `valid`: the snapshot advanced by exactly one tick on time
  // (otherwise the history restarts from this count).
  PlausibilityVerdict update(std::int64_t counts, double applied_mm_s, bool valid, const AxisModel& model,
                             double count_mm, double full_scale_mm_s, const PlausibilityLimit& limit) noexcept;
  void reset() noexcept { *this = MotionPlausibility{}; }

 private:
  std::int64_t last_counts_ = 0;
  std::uint32_t history_ = 0;  // consecutive valid ticks seen (capped)
  double last_applied_mm_s_ = 0.0;  // u_{k-2} at the next update
  std::array<double, kRunawayWindowTicks + 1> steps_mm_{};    // dp_k, dp_{k-1}, ... (newest first)
  std::array<double, kRunawayWindowTicks> applied_mm_s_{};   // u_{k-1}, u_{k-2}, ... (newest first)
};

}  // namespace tnv::fw
