#include "tools/serve/scope_ring.hpp"

#include <algorithm>
#include <stdexcept>

namespace tnv::serve {

ScopeRing::ScopeRing(std::size_t capacity) : slots_(capacity) {
  if (capacity == 0) throw std::invalid_argument("ScopeRing: capacity must be > 0");
}

void ScopeRing::push(ScopeSample sample) {
  {
    const std::lock_guard lock(mutex_);
    sample.seq = next_seq_++;
    slots_[sample.seq % slots_.size()] = sample;
    count_ = std::min(count_ + 1, slots_.size());
  }
  newer_.notify_all();
}

std::vector<ScopeSample> ScopeRing::since(std::uint64_t after, std::size_t max) const {
  const std::lock_guard lock(mutex_);
  std::vector<ScopeSample> out;
  const std::uint64_t last = next_seq_ - 1;
  const std::uint64_t oldest = last + 1 - count_;  // seq of the oldest kept sample
  for (std::uint64_t seq = std::max(after + 1, oldest); seq <= last && out.size() < max; ++seq)
    out.push_back(slots_[seq % slots_.size()]);
  return out;
}

bool ScopeRing::wait_newer(std::uint64_t after, std::chrono::milliseconds timeout) const {
  std::unique_lock lock(mutex_);
  return newer_.wait_for(lock, timeout, [&] { return next_seq_ - 1 > after; });
}

std::uint64_t ScopeRing::last_seq() const {
  const std::lock_guard lock(mutex_);
  return next_seq_ - 1;
}

std::size_t ScopeRing::size() const {
  const std::lock_guard lock(mutex_);
  return count_;
}

}  // namespace tnv::serve
