#pragma once
// On-target capture: records the selected channels (capture_channels.hpp)
// of every decimation-th tick into a fixed buffer, for upload afterwards.
//
// Trigger (capture.trigger):
//   immediate - recording starts at arm, the first sample is the next tick;
//   motion    - at the first tick of motion (state dwell or moving, or a
//               tick with motion_tick >= 0); it stops at the first tick after
//               the motion ends (state neither dwell nor moving), whose
//               sample is still recorded (off the decimation grid if need be);
//   fault     - at the tick a fault latches.
// Recording also stops when the buffer is full (capacity / channels
// samples) or on abort. Samples are sample-major, channels in bit order.
#include <array>
#include <cstdint>
#include <span>

#include "firmware/can/capture_channels.hpp"
#include "firmware/can/node_settings.hpp"
#include "firmware/can/param_table.hpp"
#include "firmware/tick/tick_record.hpp"

namespace tnv::fw::can {

// Per-tick values that are not in the TickRecord (tick_signals.hpp).
struct TickSignals {
  double contour_um = 0.0;  // S1 eq. (33) about the running circle's centre, 0 outside a circle
  double force_n = 0.0;     // force.n_per_volt x ADC volts
};

// The 32-bit word channel `bit` records for one tick (i32 channels
// rounded to their scale and saturated, f32 as float bits).
std::uint32_t channel_word(std::uint8_t bit, const TickRecord& record, const TickSignals& signals) noexcept;

class CaptureRecorder {
 public:
  // Drops the old image and waits for the trigger with these settings.
  void arm(const CaptureSettings& settings) noexcept;
  // Stops: done with the samples so far, or idle when there are none.
  void abort() noexcept;
  // Call once per tick with that tick's record (also when idle: the fault
  // trigger needs the state before arming).
  void on_tick(const TickRecord& record, const TickSignals& signals) noexcept;

  CaptureState state() const noexcept { return state_; }
  ChannelMask channel_mask() const noexcept { return mask_; }
  std::uint32_t channel_count() const noexcept { return channels_; }
  std::uint32_t decimation() const noexcept { return decimation_; }
  std::uint32_t samples() const noexcept { return samples_; }
  std::uint32_t capacity_samples() const noexcept { return channels_ == 0 ? 0 : kCaptureCapacityWords / channels_; }
  std::uint32_t image_bytes() const noexcept { return samples_ * channels_ * 4u; }
  // Byte `offset` of the image (little-endian words); 0 past its end.
  std::uint8_t image_byte(std::uint32_t offset) const noexcept;
  std::span<const std::uint32_t> words() const noexcept { return {buffer_.data(), samples_ * channels_}; }

 private:
  void record(const TickRecord& record, const TickSignals& signals) noexcept;

  CaptureState state_ = CaptureState::idle;
  CaptureTrigger trigger_ = CaptureTrigger::motion;
  ChannelMask mask_ = 0;
  std::uint32_t channels_ = 0;
  std::uint32_t decimation_ = 1;
  std::uint32_t samples_ = 0;
  std::uint32_t phase_ = 0;  // ticks since the last recorded sample
  MotionState last_state_ = MotionState::disabled;
  std::array<std::uint32_t, kCaptureCapacityWords> buffer_{};
};

}  // namespace tnv::fw::can
