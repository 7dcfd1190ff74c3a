#include "firmware/can/host_staged_sets.hpp"

namespace tnv::fw::can {

const StagedParams* HostStagedSets::find(std::uint8_t host) const noexcept {
  for (const Slot& s : slots_)
    if (!s.set.empty() && s.host == host) return &s.set;
  return nullptr;
}

StagedParams* HostStagedSets::find_or_claim(std::uint8_t host) noexcept {
  Slot* free_slot = nullptr;
  for (Slot& s : slots_) {
    if (s.set.empty()) {
      if (free_slot == nullptr) free_slot = &s;
      continue;
    }
    if (s.host == host) return &s.set;
  }
  if (free_slot == nullptr) return nullptr;
  free_slot->host = host;
  return &free_slot->set;
}

std::size_t HostStagedSets::clear(std::uint8_t host) noexcept {
  for (Slot& s : slots_) {
    if (s.set.empty() || s.host != host) continue;
    const std::size_t n = s.set.size();
    s.set.clear();
    return n;
  }
  return 0;
}

std::size_t HostStagedSets::total() const noexcept {
  std::size_t n = 0;
  for (const Slot& s : slots_) n += s.set.size();
  return n;
}

}  // namespace tnv::fw::can
