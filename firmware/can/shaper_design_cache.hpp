#pragma once
// Shaper designs the node already has, so that a parameter change never
// designs a shaper inside service(): a design takes 20-70 us of board time
// (13,000 blocks for ZVD at 30 Hz), over the real-time budget of one
// request (docs/safety.md "Real-time budget"). The defaults' designs are
// computed once per process (restore_defaults then costs a copy); a new
// spec is designed on the worker and kept here for the request that asked.
#include <array>
#include <cstddef>

#include "firmware/can/node_settings.hpp"
#include "firmware/shaper/shaper_design.hpp"
#include "hal/axis.hpp"

namespace tnv::fw::can {

// The designs of cached_default_node_settings()'s shapers, one per axis,
// computed on the first call (node construction, never service()).
const std::array<ShaperDesign, hal::kAxisCount>& cached_default_shaper_designs() noexcept;

class ShaperDesignCache {
 public:
  // Recent designs kept beside the defaults: one per axis, so a job's
  // designs for both axes are both still here when its request is replayed.
  static constexpr std::size_t kRecent = hal::kAxisCount;

  // The design of `spec`, or nullptr. Bounded: kAxisCount + kRecent compares.
  const ShaperDesign* find(const ShaperSpec& spec) const noexcept;
  // Keeps `design` for `spec`, replacing the oldest recent entry.
  void insert(const ShaperSpec& spec, const ShaperDesign& design) noexcept;

 private:
  struct Entry {
    bool used = false;
    ShaperSpec spec{};
    ShaperDesign design{};
  };
  std::array<Entry, kRecent> recent_{};
  std::size_t next_ = 0;
};

}  // namespace tnv::fw::can
