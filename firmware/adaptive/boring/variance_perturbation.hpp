#pragma once
// S4 section 5, the variance perturbation: when the measured deflection is
// outside d0 +- 3 sigma_d three or more times in a row, the process is
// assumed to have changed and P is reset to I. What "in a row" counts is a
// parameter (BoringResetCount); after a reset every count starts again.
#include <array>

#include "firmware/adaptive/boring/boring_planner_params.hpp"

namespace tnv::fw {

inline constexpr int kMaxBorePositions = 8;  // measurements per part

class VariancePerturbation {
 public:
  void configure(BoringResetCount count, int reset_after) noexcept;
  void clear() noexcept;
  // Before the RLS update of measurement `position` of the current part:
  // true = reset P now (measurement and position counting).
  bool on_measurement(int position, bool out_of_band) noexcept;
  // After the last update of a part: true = reset P now (part counting).
  bool on_part_end(bool any_out_of_band) noexcept;
  int streak() const noexcept;  // the longest current run
  // The runs themselves, to save and restore the planner (boring_planner_state.hpp).
  int run() const noexcept { return streak_; }  // measurements or parts, by the counting rule
  int position_run(int position) const noexcept;
  // Puts back runs taken from run() / position_run() (values checked by the caller).
  void restore(int run, const std::array<int, kMaxBorePositions>& position_runs) noexcept;

 private:
  BoringResetCount count_ = BoringResetCount::measurements;
  int reset_after_ = 3;
  int streak_ = 0;                          // measurements or parts
  std::array<int, kMaxBorePositions> position_streak_{};
};

}  // namespace tnv::fw
