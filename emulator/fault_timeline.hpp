#pragma once
// A fault schedule on the emulator's sub-step grid: each fault begins at the
// first 10 us boundary at or after start_s and, if it has a duration, ends
// whole sub-steps later. The machine never steps across an edge, so a fault
// starts and stops exactly where the schedule says.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "emulator/fault_schedule.hpp"

namespace tnv::emu {

struct FaultEdge {
  std::uint64_t substep = 0;
  std::size_t fault = 0;  // index into the schedule
  bool begins = true;     // false: the fault ends here
};

class FaultTimeline {
 public:
  static constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();

  FaultTimeline() = default;
  explicit FaultTimeline(std::span<const FaultSpec> faults);

  // Sub-steps from `substep` to the next pending edge (0 if one is due), kNever if none.
  std::uint64_t substeps_to_next(std::uint64_t substep) const noexcept {
    if (next_ >= edges_.size()) return kNever;
    const std::uint64_t at = edges_[next_].substep;
    return at > substep ? at - substep : 0;
  }
  // The edges due at or before `substep`, in schedule order; each is returned once.
  std::span<const FaultEdge> take_due(std::uint64_t substep) noexcept;

  std::span<const FaultEdge> edges() const noexcept { return edges_; }

 private:
  std::vector<FaultEdge> edges_;  // sorted by substep, then ends before begins, then index
  std::size_t next_ = 0;
};

// The sub-step boundary at or after t_s (t_s >= 0).
std::uint64_t substep_at_or_after(double t_s) noexcept;

}  // namespace tnv::emu
