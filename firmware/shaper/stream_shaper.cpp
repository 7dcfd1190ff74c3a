#include "firmware/shaper/stream_shaper.hpp"

#include <cmath>

namespace tnv::fw {


bool StreamShaper::request_taps(const TapSet& taps) noexcept {
  if (taps.count == 0 || taps.span() >= kRingCapacity) return false;
  for (std::size_t i = 0; i < taps.count; ++i)
    if (!std::isfinite(taps.tap[i].a)) return false;
  if (!(std::fabs(taps.sum() - 1.0) <= 1e-9)) return false;
  requested_ = taps;
  change_pending_ = true;
  return true;
}

void StreamShaper::request_enabled(bool on) noexcept {
  requested_enabled_ = on;
  change_pending_ = true;
}

void StreamShaper::fill_history(const AxisSample& value, std::uint32_t samples) noexcept {
  for (std::size_t k = 0; k <= samples; ++k) {
    const std::size_t i = (head_ - k) & kMask;
    position_mm_[i] = value.position_mm;
    speed_mm_s_[i] = value.speed_mm_s;
  }
}

void StreamShaper::apply_requested() noexcept {
  active_ = requested_;
  active_enabled_ = requested_enabled_;
  shaping_ = active_enabled_ && !active_.is_identity();
  span_ = shaping_ ? active_.span() : 0;
  change_pending_ = false;
  // Quiet: the output is the rest input; the new shaper starts from rest.
  fill_history(last_in_, span_);
  out_ = last_in_;
}

void StreamShaper::reset(const AxisSample& rest) noexcept {
  last_in_ = rest;
  rest_count_ = kRestSaturated;
  if (change_pending_) {
    apply_requested();  // fills the history
  } else {
    fill_history(rest, span_);
    out_ = rest;
  }
}

AxisSample StreamShaper::step_switching_or_shaping(const AxisSample& in) noexcept {
  if (change_pending_ && quiet()) apply_requested();
  track_rest(in);
  if (!shaping_) {  // the identity; a switch refills the history it needs from last_in_
    out_ = in;
    return out_;
  }
  head_ = (head_ + 1) & kMask;
  position_mm_[head_] = in.position_mm;
  speed_mm_s_[head_] = in.speed_mm_s;
  // y_k = x_k + sum_j a_j (x_{k-k_j} - x_k)  (S2 section 2.2, difference form)
  double dp = 0.0, dv = 0.0;
  for (std::size_t j = 0; j < active_.count; ++j) {
    const Tap& t = active_.tap[j];
    const std::size_t i = (head_ - t.k) & kMask;
    dp += t.a * (position_mm_[i] - in.position_mm);
    dv += t.a * (speed_mm_s_[i] - in.speed_mm_s);
  }
  out_ = {in.position_mm + dp, in.speed_mm_s + dv};
  return out_;
}

void shape_offline(const TapSet& taps, const AxisSample* in, AxisSample* out, std::size_t n,
                   const AxisSample& rest) noexcept {
  for (std::size_t k = 0; k < n; ++k) {
    const AxisSample& x = in[k];
    double dp = 0.0, dv = 0.0;
    for (std::size_t j = 0; j < taps.count; ++j) {
      const Tap& t = taps.tap[j];
      const AxisSample& h = t.k <= k ? in[k - t.k] : rest;
      dp += t.a * (h.position_mm - x.position_mm);
      dv += t.a * (h.speed_mm_s - x.speed_mm_s);
    }
    out[k] = {x.position_mm + dp, x.speed_mm_s + dv};
  }
}

}  // namespace tnv::fw
