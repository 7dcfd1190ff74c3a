#include "firmware/shaper/path_taps.hpp"

namespace tnv::fw {

bool same_taps(const TapSet& a, const TapSet& b) noexcept {
  if (a.count != b.count) return false;
  for (std::size_t i = 0; i < a.count; ++i)
    if (a.tap[i].k != b.tap[i].k || a.tap[i].a != b.tap[i].a) return false;
  return true;
}

bool path_taps(const std::array<AxisShaperChoice, hal::kAxisCount>& axes, std::uint32_t max_span_samples,
               TapSet& out) noexcept {
  TapSet series = TapSet::identity();
  std::array<const TapSet*, hal::kAxisCount> used{};
  std::size_t n_used = 0;
  for (const AxisShaperChoice& a : axes) {
    if (!a.enabled || a.taps == nullptr) continue;
    bool seen = false;
    for (std::size_t j = 0; j < n_used; ++j) seen = seen || same_taps(*used[j], *a.taps);
    if (seen) continue;  // the same design on two axes runs once
    // The product of two z-polynomials has at most count_a x count_b taps.
    if (series.count * a.taps->count > TapSet::kCapacity) return false;
    if (series.span() + a.taps->span() >= max_span_samples) return false;
    series = convolve(series, *a.taps);
    used[n_used++] = a.taps;
  }
  out = series;
  return true;
}

}  // namespace tnv::fw
