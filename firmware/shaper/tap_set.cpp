#include "firmware/shaper/tap_set.hpp"

namespace tnv::fw {

bool TapSet::add(std::uint32_t k, double a) noexcept {
  std::size_t i = 0;
  while (i < count && tap[i].k < k) ++i;
  if (i < count && tap[i].k == k) {
    tap[i].a += a;
    return true;
  }
  if (count == kCapacity) return false;
  for (std::size_t j = count; j > i; --j) tap[j] = tap[j - 1];
  tap[i] = {k, a};
  ++count;
  return true;
}

TapSet convolve(const TapSet& a, const TapSet& b) noexcept {
  TapSet out;
  for (std::size_t i = 0; i < a.count; ++i)
    for (std::size_t j = 0; j < b.count; ++j) out.add(a.tap[i].k + b.tap[j].k, a.tap[i].a * b.tap[j].a);
  return out;
}

}  // namespace tnv::fw
