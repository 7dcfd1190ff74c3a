#pragma once
// [io]: the register transport between the firmware's CPU and the I/O
// board, as an SPI or Ethernet link on a Linux controller board
// (docs/scenarios.md "Transport timing", docs/hil-rig.md). Board clocks
// throughout (10 MHz, counted since reset).
//
//   a tick latches at L; the snapshot read completes at L + r,
//     r = read_latency_us + U[0, jitter_us]                 (drawn at the latch)
//   the firmware works W after that (what the rig metered; 0 when not told)
//   its output transfer, issued at t (t = L on the in-process rig), lands at
//     max(t, L + r) + W + w,  w = write_latency_us + U[0, jitter_us]
//   rounded up to the next 10 us sub-step boundary (the emulator's time grid),
//   and never before the transfer issued ahead of it (the link keeps order).
// At most kMaxInFlight transfers wait; one more lands the oldest at once.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "emulator/io_board.hpp"
#include "emulator/noise_stream.hpp"
#include "emulator/scenario.hpp"
#include "emulator/substep_timing.hpp"

namespace tnv::emu {

class OutputTransport {
 public:
  static constexpr std::size_t kMaxInFlight = 4;
  static constexpr std::uint64_t kNone = std::numeric_limits<std::uint64_t>::max();

  OutputTransport(const IoParams& io, std::uint32_t seed)
      : read_ns_(io.read_latency_us * 1000.0),
        write_ns_(io.write_latency_us * 1000.0),
        jitter_ns_(io.jitter_us * 1000.0),
        enabled_(io.enabled()),
        jitter_(make_noise_stream(seed, NoiseStreamId::io_jitter)) {}

  bool enabled() const noexcept { return enabled_; }

  // A tick latched now: draws this tick's read delay; returns it in whole clocks (for CLOCK_AT_READ).
  std::uint32_t on_latch(std::uint64_t latch_clocks) noexcept {
    latch_clocks_ = latch_clocks;
    read_delay_ns_ = read_ns_ + draw_jitter_ns();
    return static_cast<std::uint32_t>(std::ceil(read_delay_ns_ / kClockNs - kRoundingSlack));
  }
  // The firmware's work between the read and its write, this tick (board time).
  void set_work_ns(double work_ns) noexcept { work_ns_ = work_ns; }

  // Output words written by `now_clocks` go out; returns the clock they land at.
  // The queue must not be full (land take_oldest() first).
  std::uint64_t send(const OutputWords& words, std::uint64_t now_clocks) noexcept {
    const double issued_ns = std::max(static_cast<double>(now_clocks - latch_clocks_) * kClockNs, read_delay_ns_);
    const double landing_ns = issued_ns + work_ns_ + write_ns_ + draw_jitter_ns();
    work_ns_ = 0.0;
    const auto substeps = static_cast<std::uint64_t>(std::ceil(landing_ns / kSubstepNs - kRoundingSlack));
    std::uint64_t landing_clocks = latch_clocks_ + substeps * kSubstepClocks;
    if (count_ > 0) landing_clocks = std::max(landing_clocks, queue_[(head_ + count_ - 1) % kMaxInFlight].landing_clocks);
    queue_[(head_ + count_) % kMaxInFlight] = {words, landing_clocks};
    ++count_;
    return landing_clocks;
  }
  bool full() const noexcept { return count_ == kMaxInFlight; }
  // The oldest transfer in flight lands at or before `now_clocks`.
  bool due(std::uint64_t now_clocks) const noexcept { return count_ > 0 && queue_[head_].landing_clocks <= now_clocks; }
  OutputWords take_oldest() noexcept {
    const OutputWords words = queue_[head_].words;
    head_ = (head_ + 1) % kMaxInFlight;
    --count_;
    return words;
  }
  // Whole sub-steps from `now_clocks` to the next landing (>= 1), or kNone.
  std::uint64_t substeps_to_next_landing(std::uint64_t now_clocks) const noexcept {
    if (count_ == 0) return kNone;
    const std::uint64_t at = queue_[head_].landing_clocks;
    return at > now_clocks ? (at - now_clocks + kSubstepClocks - 1) / kSubstepClocks : 1;
  }

 private:
  static constexpr double kClockNs = 1e9 / static_cast<double>(kClockHz);
  static constexpr double kSubstepNs = kClockNs * static_cast<double>(kSubstepClocks);
  static constexpr double kRoundingSlack = 1e-9;  // 150 us is 15 sub-steps, not 16

  double draw_jitter_ns() noexcept { return jitter_ns_ > 0.0 ? jitter_ns_ * jitter_.uniform() : 0.0; }

  struct InFlight {
    OutputWords words;
    std::uint64_t landing_clocks = 0;
  };

  double read_ns_, write_ns_, jitter_ns_;
  bool enabled_;
  NoiseStream jitter_;
  std::uint64_t latch_clocks_ = 0;
  double read_delay_ns_ = 0.0;
  double work_ns_ = 0.0;
  std::array<InFlight, kMaxInFlight> queue_{};
  std::size_t head_ = 0, count_ = 0;
};

}  // namespace tnv::emu
