#pragma once
// The scope history shared by the node thread (the one writer) and the
// telemetry streams (readers): a fixed-capacity ring of samples, so a
// slow or absent reader never makes it grow, and a wait for the next
// sample that a stream blocks on between batches.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <vector>

#include "tools/serve/telemetry_sample.hpp"

namespace tnv::serve {

class ScopeRing {
 public:
  explicit ScopeRing(std::size_t capacity);

  // Gives the sample the next sequence number, drops the oldest when full.
  void push(ScopeSample sample);
  // Samples with seq > `after`, oldest first, at most `max`; a reader that
  // fell behind the ring gets what is left (the oldest kept first).
  std::vector<ScopeSample> since(std::uint64_t after, std::size_t max) const;
  // Until a sample with seq > `after` exists or `timeout` passes; true if one does.
  bool wait_newer(std::uint64_t after, std::chrono::milliseconds timeout) const;
  std::uint64_t last_seq() const;
  std::size_t size() const;
  std::size_t capacity() const noexcept { return slots_.size(); }

 private:
  mutable std::mutex mutex_;
  mutable std::condition_variable newer_;
  std::vector<ScopeSample> slots_;
  std::uint64_t next_seq_ = 1;
  std::size_t count_ = 0;
};

}  // namespace tnv::serve
