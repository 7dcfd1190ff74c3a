#include "firmware/shaper/impulse_train.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::fw {

ImpulseTrain convolve(const ImpulseTrain& a, const ImpulseTrain& b) noexcept {
  ImpulseTrain out;
  for (std::size_t i = 0; i < a.count; ++i)
    for (std::size_t j = 0; j < b.count; ++j)
      out.push(a.impulse[i].t_s + b.impulse[j].t_s, a.impulse[i].a * b.impulse[j].a);
  std::sort(out.impulse.begin(), out.impulse.begin() + static_cast<std::ptrdiff_t>(out.count),
            [](const Impulse& x, const Impulse& y) { return x.t_s < y.t_s; });
  // Merge impulses that coincide (e.g. 30 Hz x 60 Hz ZV share times).
  std::size_t n = 0;
  for (std::size_t i = 0; i < out.count; ++i) {
    if (n > 0 && std::fabs(out.impulse[i].t_s - out.impulse[n - 1].t_s) <= 1e-12) {
      out.impulse[n - 1].a += out.impulse[i].a;
    } else {
      out.impulse[n++] = out.impulse[i];
    }
  }
  out.count = n;
  return out;
}

}  // namespace tnv::fw
