#pragma once
// One pending parameter set per host (the host id of the request tag), so
// that a commit or a discard acts on the requesting host's stages only.
// Fixed capacity: kMaxStagingHosts hosts may hold a non-empty set at once;
// a further host's stage is refused (busy) until one of them commits or
// discards. No allocation.
#include <array>
#include <cstddef>
#include <cstdint>

#include "firmware/can/staged_params.hpp"

namespace tnv::fw::can {

inline constexpr std::size_t kMaxStagingHosts = 4;

class HostStagedSets {
 public:
  // The host's set, nullptr when it has none (nothing staged).
  const StagedParams* find(std::uint8_t host) const noexcept;
  // The host's set, or a free one now assigned to it; nullptr when every set is taken by other hosts.
  StagedParams* find_or_claim(std::uint8_t host) noexcept;
  // Drops the host's set; returns how many parameters it held.
  std::size_t clear(std::uint8_t host) noexcept;
  std::size_t total() const noexcept;  // staged parameters over all hosts
  bool empty() const noexcept { return total() == 0; }

 private:
  struct Slot {
    std::uint8_t host = 0;  // meaningful while set is not empty
    StagedParams set{};
  };
  std::array<Slot, kMaxStagingHosts> slots_{};
};

}  // namespace tnv::fw::can
