#include "tools/score/contour_stats.hpp"

#include <algorithm>

namespace tnv::hil {

void ContourAccumulator::add(double error_mm) noexcept {
  const double e_um = error_mm * 1000.0;
  ++n_;
  max_um_ = std::max(max_um_, e_um);
  const double delta = e_um - mean_um_;
  mean_um_ += delta / static_cast<double>(n_);
  m2_um2_ += delta * (e_um - mean_um_);
}

ContourStats ContourAccumulator::stats() const noexcept {
  if (n_ == 0) return {};
  return {max_um_, mean_um_, std::sqrt(m2_um2_ / static_cast<double>(n_)), n_};
}

ContourStats average(std::span<const ContourStats> runs) noexcept {
  ContourStats out;
  if (runs.empty()) return out;
  for (const ContourStats& r : runs) {
    out.max_um += r.max_um;
    out.mean_um += r.mean_um;
    out.std_um += r.std_um;
    out.samples += r.samples;
  }
  const double n = static_cast<double>(runs.size());
  out.max_um /= n;
  out.mean_um /= n;
  out.std_um /= n;
  return out;
}

}  // namespace tnv::hil
