#include "firmware/homing/homing_cycle.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::fw {

HomingParams machine_homing_params(hal::Axis axis) noexcept {
  HomingParams p;
  switch (axis) {
    case hal::Axis::x:
    case hal::Axis::y:
      break;
    case hal::Axis::z:
      p.search_positive = true;
      break;
  }
  return p;
}

ParamCheck validate(const HomingParams& p) noexcept {
  if (!std::isfinite(p.search_mm_s) || p.search_mm_s <= 0.0)
    return param_error(&p.search_mm_s, "search_mm_s", "must be > 0 and finite");
  if (!std::isfinite(p.latch_mm_s) || p.latch_mm_s <= 0.0)
    return param_error(&p.latch_mm_s, "latch_mm_s", "must be > 0 and finite");
  if (p.latch_mm_s > p.search_mm_s) return param_error(&p.latch_mm_s, "latch_mm_s", "must be <= search_mm_s");
  if (!std::isfinite(p.position_mm)) return param_error(&p.position_mm, "position_mm", "must be finite");
  if (!std::isfinite(p.search_max_mm) || p.search_max_mm <= 0.0)
    return param_error(&p.search_max_mm, "search_max_mm", "must be > 0 and finite");
  if (!std::isfinite(p.latch_max_mm) || p.latch_max_mm <= 0.0)
    return param_error(&p.latch_max_mm, "latch_max_mm", "must be > 0 and finite");
  return {};
}

void HomingCycle::start(const HomingParams& params, double accel_mm_s2, double position_mm, double tick_s) noexcept {
  params_ = params;
  accel_mm_s2_ = accel_mm_s2;
  tick_s_ = tick_s;
  position_mm_ = position_mm;
  speed_mm_s_ = 0.0;
  phase_start_mm_ = position_mm;
  target_mm_s_ = params.search_positive ? params.search_mm_s : -params.search_mm_s;
  phase_ = HomingPhase::search;
  result_ = HomingResult::running;
  pending_ = HomingResult::none;
  failed_travel_mm_ = 0.0;
  failed_limit_mm_ = 0.0;
}

void HomingCycle::fail(HomingResult why, double travel_mm, double limit_mm) noexcept {
  pending_ = why;
  failed_travel_mm_ = travel_mm;
  failed_limit_mm_ = limit_mm;
  target_mm_s_ = 0.0;
  phase_ = HomingPhase::failing_stop;
}

void HomingCycle::abort() noexcept {
  if (!running() || phase_ == HomingPhase::failing_stop) return;
  fail(HomingResult::aborted, std::fabs(position_mm_ - phase_start_mm_), 0.0);
}

HomingStep HomingCycle::step(bool switch_on, std::uint8_t index_edges) noexcept {
  HomingStep out;
  const double toward_switch = params_.search_positive ? 1.0 : -1.0;
  const double travel_mm = std::fabs(position_mm_ - phase_start_mm_);
  switch (phase_) {
    case HomingPhase::search:
      if (switch_on) {
        phase_ = HomingPhase::search_stop;
        target_mm_s_ = 0.0;
      } else if (travel_mm >= params_.search_max_mm) {
        fail(HomingResult::switch_not_found, travel_mm, params_.search_max_mm);
      }
      break;
    case HomingPhase::search_stop:
      if (speed_mm_s_ == 0.0) {
        phase_ = HomingPhase::back_off;
        phase_start_mm_ = position_mm_;
        target_mm_s_ = -toward_switch * params_.latch_mm_s;
      }
      break;
    case HomingPhase::back_off:
      if (!switch_on) {
        // Released: the next index edge after this snapshot's count is home.
        phase_ = HomingPhase::find_index;
        phase_start_mm_ = position_mm_;
        edges_at_release_ = index_edges;
      } else if (travel_mm >= params_.latch_max_mm) {
        fail(HomingResult::switch_not_released, travel_mm, params_.latch_max_mm);
      }
      break;
    case HomingPhase::find_index:
      if (index_edges != edges_at_release_) {
        out.index_found = true;
        phase_ = HomingPhase::final_stop;
        target_mm_s_ = 0.0;
      } else if (travel_mm >= params_.latch_max_mm) {
        fail(HomingResult::index_not_found, travel_mm, params_.latch_max_mm);
      }
      break;
    case HomingPhase::final_stop:
      if (speed_mm_s_ == 0.0) {
        phase_ = HomingPhase::done;
        result_ = HomingResult::homed;
      }
      break;
    case HomingPhase::failing_stop:
      if (speed_mm_s_ == 0.0) {
        phase_ = HomingPhase::failed;
        result_ = pending_;
      }
      break;
    case HomingPhase::idle:
    case HomingPhase::done:
    case HomingPhase::failed: break;
  }
  // The reference: constant acceleration toward the phase's target speed.
  out.now = {position_mm_, speed_mm_s_};
  const double dv = accel_mm_s2_ * tick_s_;
  const double v = target_mm_s_ > speed_mm_s_ ? std::min(speed_mm_s_ + dv, target_mm_s_)
                                              : std::max(speed_mm_s_ - dv, target_mm_s_);
  position_mm_ += 0.5 * (speed_mm_s_ + v) * tick_s_;
  speed_mm_s_ = v;
  out.next = {position_mm_, speed_mm_s_};
  return out;
}

}  // namespace tnv::fw
