#pragma once
// The spindle's encoder (reference plant "Spindle"): counts_per_rev after x4
// decoding and one index pulse per revolution at index_deg. Fed the
// spindle's revolutions sub-step by sub-step; counts the index edges and
// latches the count at the last one (as the board latches the axes'
// index, which it will do for this channel once it is wired).
#include <cmath>
#include <cstdint>

#include "emulator/quadrature_encoder.hpp"
#include "emulator/scenario.hpp"

namespace tnv::emu {

class SpindleEncoder {
 public:
  explicit SpindleEncoder(const SpindleParams& params, double start_revolutions = 0.0) noexcept
      : counter_(1.0 / params.encoder_counts_per_rev, 0.0),
        index_rev_(params.index_deg / 360.0),
        revolutions_(start_revolutions) {}

  // The spindle has turned to `revolutions` since the last call.
  void follow(double revolutions) noexcept {
    // Marks at index_rev + k; crossing one (either way) is an edge.
    const double k_from = std::floor(revolutions_ - index_rev_);
    const double k_to = std::floor(revolutions - index_rev_);
    if (k_from != k_to) {
      index_edges_ += static_cast<std::uint64_t>(std::abs(k_to - k_from));
      // The last mark crossed: the highest going forward, the lowest going back.
      latched_count_ = counter_.count(index_rev_ + (k_to > k_from ? k_to : k_to + 1.0));
    }
    revolutions_ = revolutions;
  }

  std::int64_t count() const noexcept { return counter_.count(revolutions_); }
  std::uint64_t index_edges() const noexcept { return index_edges_; }
  std::int64_t latched_count() const noexcept { return latched_count_; }  // count at the last index edge

 private:
  QuadratureEncoder counter_;  // "mm" here are revolutions
  double index_rev_;
  double revolutions_;
  std::uint64_t index_edges_ = 0;
  std::int64_t latched_count_ = 0;
};

}  // namespace tnv::emu
