#pragma once
// The shaper every axis of the path runs (shaped axes stay in step): the
// enabled axes' grid shapers in series, each distinct design once. Every
// axis is then filtered, and delayed, alike, so shaping one axis never
// bends a contour: a line stays the same line, a corner is rounded the same
// way on both axes. Series of shapers keep every mode's zeros, so each
// axis still gets its own mode suppressed.
#include <array>
#include <cstddef>

#include "firmware/shaper/tap_set.hpp"
#include "hal/axis.hpp"

namespace tnv::fw {

struct AxisShaperChoice {
  const TapSet* taps = nullptr;  // the axis' design; nullptr when not configured
  bool enabled = false;
};

// The identity when no axis is enabled. False (out untouched) when the
// series would not fit a TapSet or a span of `max_span_samples`.
bool path_taps(const std::array<AxisShaperChoice, hal::kAxisCount>& axes, std::uint32_t max_span_samples,
               TapSet& out) noexcept;

bool same_taps(const TapSet& a, const TapSet& b) noexcept;

}  // namespace tnv::fw
