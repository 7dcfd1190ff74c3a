#include "firmware/adaptive/boring/variance_perturbation.hpp"

#include <algorithm>

namespace tnv::fw {

void VariancePerturbation::configure(BoringResetCount count, int reset_after) noexcept {
  count_ = count;
  reset_after_ = reset_after;
  clear();
}

void VariancePerturbation::clear() noexcept {
  streak_ = 0;
  position_streak_.fill(0);
}

bool VariancePerturbation::on_measurement(int position, bool out_of_band) noexcept {
  if (count_ == BoringResetCount::measurements) {
    streak_ = out_of_band ? streak_ + 1 : 0;
    if (streak_ < reset_after_) return false;
  } else if (count_ == BoringResetCount::positions) {
    if (position < 0 || position >= kMaxBorePositions) return false;
    int& s = position_streak_[static_cast<std::size_t>(position)];
    s = out_of_band ? s + 1 : 0;
    if (s < reset_after_) return false;
  } else {
    return false;
  }
  clear();
  return true;
}

bool VariancePerturbation::on_part_end(bool any_out_of_band) noexcept {
  if (count_ != BoringResetCount::parts) return false;
  streak_ = any_out_of_band ? streak_ + 1 : 0;
  if (streak_ < reset_after_) return false;
  clear();
  return true;
}

int VariancePerturbation::position_run(int position) const noexcept {
  if (position < 0 || position >= kMaxBorePositions) return 0;
  return position_streak_[static_cast<std::size_t>(position)];
}

void VariancePerturbation::restore(int run, const std::array<int, kMaxBorePositions>& position_runs) noexcept {
  streak_ = run;
  position_streak_ = position_runs;
}

int VariancePerturbation::streak() const noexcept {
  int s = streak_;
  for (int p : position_streak_) s = std::max(s, p);
  return s;
}

}  // namespace tnv::fw
