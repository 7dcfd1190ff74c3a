#include "emulator/fault_timeline.hpp"

#include <algorithm>
#include <cmath>

#include "emulator/substep_timing.hpp"

namespace tnv::emu {

std::uint64_t substep_at_or_after(double t_s) noexcept {
  // A hair of slack so 0.003 s lands on boundary 300, not 301.
  const double substeps = std::ceil(t_s * static_cast<double>(kSubstepsPerSecond) - 1e-6);
  return substeps <= 0.0 ? 0 : static_cast<std::uint64_t>(substeps);
}

FaultTimeline::FaultTimeline(std::span<const FaultSpec> faults) {
  for (std::size_t i = 0; i < faults.size(); ++i) {
    const FaultSpec& f = faults[i];
    const std::uint64_t begin = substep_at_or_after(f.start_s);
    edges_.push_back({begin, i, true});
    if (fault_keys(f.kind).duration && f.duration_s > 0.0) {
      const std::uint64_t length = std::max<std::uint64_t>(1, substep_at_or_after(f.duration_s));
      edges_.push_back({begin + length, i, false});
    }
  }
  // At one boundary a fault that ends goes before one that begins, so
  // back-to-back windows of the same kind hand over cleanly.
  std::stable_sort(edges_.begin(), edges_.end(), [](const FaultEdge& a, const FaultEdge& b) {
    if (a.substep != b.substep) return a.substep < b.substep;
    return !a.begins && b.begins;
  });
}

std::span<const FaultEdge> FaultTimeline::take_due(std::uint64_t substep) noexcept {
  const std::size_t first = next_;
  while (next_ < edges_.size() && edges_[next_].substep <= substep) ++next_;
  return std::span<const FaultEdge>(edges_).subspan(first, next_ - first);
}

}  // namespace tnv::emu
