#pragma once
// Real-time buffered input shaping (S2 section 2.2) of one axis' reference
// stream, position and speed alike: every tick one command sample goes in
// and one shaped sample comes out,
//   y_k = x_k + sum_j a_j (x_{k - k_j} - x_k)      (= sum_j a_j x_{k - k_j}, as sum a_j = 1)
// from a ring buffer of past inputs sized for the longest shaper. The
// difference form makes a stream at rest come out bit-exactly at rest, so
// the final position and the travel of a move are unchanged to the bit.
// It handles an unbounded live stream (operator jog): nothing grows.
// shape_offline() is the same sum over a whole recorded stream; the two
// agree exactly.
//
// Configuration is requested between ticks and applied only when the
// buffer is quiet: the last (span + 1) inputs identical and at rest, so
// the active shaper's output equals its input. The ring is then refilled
// with that rest sample and the new shaper starts from rest: no jump in
// position or speed. Taps and enable are separate requests; disabled is
// the identity (output = input, bit for bit). No allocation anywhere.
#include <array>
#include <cstddef>
#include <cstdint>

#include "firmware/shaper/tap_set.hpp"
#include "firmware/trajectory/plane_reference.hpp"

namespace tnv::fw {

class StreamShaper {
 public:
  // Power of two. The longest shaper of the design range (two ZVDD at 5 Hz,
  // zeta 0.3) spans 630 samples (shaper_design TheLongestShaperFitsTheRing).
  static constexpr std::size_t kRingCapacity = 1024;

  StreamShaper() noexcept { reset({}); }

  // --- configuration (between ticks), applied at the next quiet point.
  // False (nothing changes) for an empty set, a span that does not fit the
  // ring, non-finite taps or taps not summing to 1 (within 1e-9).
  bool request_taps(const TapSet& taps) noexcept;
  void request_enabled(bool on) noexcept;

  // --- streaming
  AxisSample step(const AxisSample& in) noexcept {
    if (!shaping_ && !change_pending_) {  // off, nothing waiting: the identity (inline: the tick's usual case)
      track_rest(in);
      out_ = in;
      return out_;
    }
    return step_switching_or_shaping(in);
  }
  // Declares the stream at rest at `rest` (servo off, or a deliberate
  // restart): any requested change is applied at once.
  void reset(const AxisSample& rest) noexcept;

  // --- status
  bool shaping() const noexcept { return shaping_; }  // active: enabled, taps not the identity
  bool change_pending() const noexcept { return change_pending_; }
  bool quiet() const noexcept { return rest_count_ > span_; }
  const AxisSample& output() const noexcept { return out_; }
  std::uint32_t span_samples() const noexcept { return shaping_ ? active_.span() : 0; }
  double delay_samples() const noexcept { return shaping_ ? active_.centroid_samples() : 0.0; }
  bool enabled() const noexcept { return active_enabled_; }
  bool requested_enabled() const noexcept { return requested_enabled_; }
  const TapSet& active_taps() const noexcept { return active_; }

 private:
  static constexpr std::size_t kMask = kRingCapacity - 1;
  static constexpr std::uint32_t kRestSaturated = 0x7FFFFFFFu;
  static_assert((kRingCapacity & kMask) == 0, "ring capacity must be a power of two");
  AxisSample step_switching_or_shaping(const AxisSample& in) noexcept;
  void apply_requested() noexcept;
  // Consecutive inputs equal to their predecessor with speed 0 (saturating).
  void track_rest(const AxisSample& in) noexcept {
    const bool at_rest = in.speed_mm_s == 0.0 && in.position_mm == last_in_.position_mm;
    rest_count_ = at_rest ? (rest_count_ < kRestSaturated ? rest_count_ + 1 : rest_count_) : 0;
    last_in_ = in;
  }
  void fill_history(const AxisSample& value, std::uint32_t samples) noexcept;

  // What every tick touches first, on one cache line; the bulk after it.
  bool active_enabled_ = false;
  bool requested_enabled_ = false;
  bool change_pending_ = false;
  bool shaping_ = false;
  std::uint32_t span_ = 0;        // longest delay of the active shaper (0 when not shaping)
  std::uint32_t rest_count_ = 0;  // consecutive inputs equal to their predecessor with speed 0
  std::size_t head_ = 0;          // index of the newest input
  AxisSample last_in_{};
  AxisSample out_{};
  TapSet active_ = TapSet::identity();
  std::array<double, kRingCapacity> position_mm_{};
  std::array<double, kRingCapacity> speed_mm_s_{};
  TapSet requested_ = TapSet::identity();
};

// The same shaping over a recorded stream in[0..n) (history before it at
// rest at `rest`), into out[0..n).
void shape_offline(const TapSet& taps, const AxisSample* in, AxisSample* out, std::size_t n,
                   const AxisSample& rest) noexcept;

}  // namespace tnv::fw
