#include "firmware/adaptive/arsc/arsc_feed_source.hpp"

#include <algorithm>
#include <cmath>

#include "firmware/motion/motion_interpolator.hpp"

namespace tnv::fw::arsc {

ArscFeedSource::ArscFeedSource() noexcept : loop_(outer_config(ArscSourceParams{})) {
  status_.cutting_gain_n_per_mm_s = loop_.cutting_gain_n_per_mm_s();
}

ParamCheck ArscFeedSource::configure(const ArscSourceParams& params) noexcept {
  if (const ParamCheck check = validate(params); !check.ok) return check;
  params_ = params;
  loop_ = OuterArsc(outer_config(params));
  running_ = false;
  was_cutting_ = false;
  status_ = ArscSourceStatus{};
  status_.state = params_.enabled ? ArscSourceState::waiting : ArscSourceState::off;
  status_.cutting_gain_n_per_mm_s = loop_.cutting_gain_n_per_mm_s();
  return param_ok();
}

bool ArscFeedSource::set_force_ref_n(double force_ref_n) noexcept {
  if (!std::isfinite(force_ref_n) || !(force_ref_n >= 0.0)) return false;
  params_.force_ref_n = force_ref_n;
  return true;
}

void ArscFeedSource::start(const std::array<double, 2>& position_mm) noexcept {
  loop_.reset();  // a new cut starts from the model's cutting gain
  running_ = true;
  was_cutting_ = false;
  phase_ticks_ = 0;
  cutting_ticks_ = 0;
  last_sample_mm_ = position_mm;
  status_.state = ArscSourceState::paused;
  status_.force_ref_n = 0.0;
  status_.command_mm_s = 0.0;
  status_.feed_override = 0.0;
  status_.clamped = false;
  status_.samples = status_.clamped_samples = status_.refused_designs = 0;
  status_.cutting_gain_n_per_mm_s = loop_.cutting_gain_n_per_mm_s();
}

void ArscFeedSource::stop() noexcept {
  running_ = false;
  was_cutting_ = false;
  status_.state = params_.enabled ? ArscSourceState::waiting : ArscSourceState::off;
  status_.force_ref_n = 0.0;
}

double ArscFeedSource::tick(const ArscFeedInput& in) noexcept {
  // The range this tick: the operator's override scales the loop's range (1,
  // each program's start value: [override_min, override_max]; 0 holds the path).
  const double op = std::isfinite(in.operator_override)
                        ? std::clamp(in.operator_override, 0.0, motion::kMaxFeedOverride)
                        : 0.0;
  const double hi_ratio = std::min(params_.override_max * op, motion::kMaxFeedOverride);
  const double lo_ratio = std::min(params_.override_min * op, hi_ratio);
  const double feed_mm_s = in.programmed_feed_mm_s;
  if (!running_ || !(feed_mm_s > 0.0) || !std::isfinite(feed_mm_s)) {
    // Not cutting: no sample (the force falls with the feed, and an integrator
    // fed by that would wind up); the command is held for the resume.
    was_cutting_ = false;
    if (running_) status_.state = ArscSourceState::paused;
    status_.feed_override = std::clamp(status_.feed_override, lo_ratio, hi_ratio);
    return status_.feed_override;
  }
  if (!was_cutting_) {
    // The cut (re)starts: sample now, soft start from 0. After a pause the
    // compensator restarts and the estimate stays (start() reset it all).
    if (status_.state == ArscSourceState::paused && cutting_ticks_ > 0) loop_.restart();
    was_cutting_ = true;
    phase_ticks_ = 0;
    cutting_ticks_ = 0;
    last_sample_mm_ = in.position_mm;
    status_.command_mm_s = 0.0;
  }
  status_.state = ArscSourceState::cutting;
  if (phase_ticks_ == 0) sample(in, lo_ratio, hi_ratio);
  phase_ticks_ = phase_ticks_ + 1 >= params_.period_ticks ? 0 : phase_ticks_ + 1;
  ++cutting_ticks_;
  // The feed command is held between samples; its ratio follows the element's programmed feed.
  status_.feed_override = std::clamp(status_.command_mm_s / feed_mm_s, lo_ratio, hi_ratio);
  return status_.feed_override;
}

void ArscFeedSource::sample(const ArscFeedInput& in, double lo_ratio, double hi_ratio) noexcept {
  const double period_s = kArscTickS * static_cast<double>(params_.period_ticks);
  const double elapsed_s = kArscTickS * static_cast<double>(cutting_ticks_);
  const double ramp = params_.soft_start_s > 0.0 ? std::min(1.0, elapsed_s / params_.soft_start_s) : 1.0;
  status_.force_ref_n = ramp * params_.force_ref_n;
  // The feed along the path, whatever its direction: what the cut sees
  // through the programmed path (the cutting gain absorbs the direction).
  const double travel_mm = std::hypot(in.position_mm[0] - last_sample_mm_[0], in.position_mm[1] - last_sample_mm_[1]);
  last_sample_mm_ = in.position_mm;
  const double mean_feed_mm_s = travel_mm / period_s;
  const double feed_mm_s = std::hypot(in.speed_mm_s[0], in.speed_mm_s[1]);
  loop_.set_force_ref_n(status_.force_ref_n);
  (void)loop_.set_feed_range_mm_s(lo_ratio * in.programmed_feed_mm_s, hi_ratio * in.programmed_feed_mm_s);
  status_.command_mm_s = loop_.step(in.force_n, feed_mm_s, mean_feed_mm_s);
  const OuterArscSignals& s = loop_.signals();
  status_.force_n = in.force_n;
  status_.clamped = s.clamped;
  status_.cutting_gain_n_per_mm_s = loop_.cutting_gain_n_per_mm_s();
  ++status_.samples;
  status_.clamped_samples += s.clamped ? 1u : 0u;
  std::uint32_t refused = 0;
  for (std::size_t i = 1; i < s.reason_counts.size(); ++i) refused += s.reason_counts[i];
  status_.refused_designs = refused;
}

}  // namespace tnv::fw::arsc
