// PathShapers: planning the path's series and shaping each axis' reference.
#include "firmware/tick/path_shapers.hpp"

#include <cstdint>

namespace tnv::fw {

bool PathShapers::plan(const std::array<AxisShaperChoice, hal::kAxisCount>& axes) noexcept {
  TapSet series;
  if (!path_taps(axes, static_cast<std::uint32_t>(StreamShaper::kRingCapacity), series)) return false;
  path_taps_ = series;
  path_shaping_ = !series.is_identity();
  change_pending_ = true;
  return true;
}

bool PathShapers::configure(std::size_t a, const ShaperDesign& design) noexcept {
  std::array<AxisShaperChoice, hal::kAxisCount> axes{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    axes[i] = {i == a ? &design.taps : (axis_[i].configured ? &axis_[i].design.taps : nullptr), axis_[i].enabled};
  if (!plan(axes)) return false;
  axis_[a].design = design;
  axis_[a].configured = true;
  return true;
}

bool PathShapers::enable(std::size_t a, bool on) noexcept {
  if (on && !axis_[a].configured) return false;
  std::array<AxisShaperChoice, hal::kAxisCount> axes{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    axes[i] = {axis_[i].configured ? &axis_[i].design.taps : nullptr, i == a ? on : axis_[i].enabled};
  if (!plan(axes)) return false;
  axis_[a].enabled = on;
  return true;
}

void PathShapers::forward_when_quiet(bool servo_off) noexcept {
  if (!change_pending_) return;
  bool all_quiet = true;
  for (const AxisShaping& s : axis_) all_quiet = all_quiet && s.shaper.quiet();
  if (!all_quiet && !servo_off) return;
  for (AxisShaping& s : axis_) {
    if (path_shaping_) (void)s.shaper.request_taps(path_taps_);  // fits: checked by plan()
    s.shaper.request_enabled(path_shaping_);
  }
  change_pending_ = false;
}

PathShapers::Pair PathShapers::shape(std::size_t i, const AxisSample& now, const AxisSample& next) noexcept {
  StreamShaper& shaper = axis_[i].shaper;
  if (!shaper.shaping() && !shaper.change_pending()) {
    shaper.step(next);   // the identity; it only notes whether the stream rests
    return {now, next};  // off: the unshaped path, bit for bit
  }
  const bool was_shaping = shaper.shaping();
  const AxisSample shaped_now = shaper.output();
  const AxisSample shaped_next = shaper.step(next);
  if (!was_shaping && !shaper.shaping()) return {now, next};  // off: the unshaped path, bit for bit
  return {shaped_now, shaped_next};
}

bool PathShapers::settled() const noexcept {
  for (const AxisShaping& s : axis_)
    if (s.shaper.shaping() && !s.shaper.quiet()) return false;
  return true;
}

}  // namespace tnv::fw
