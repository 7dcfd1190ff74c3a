#include "firmware/can/capture_recorder.hpp"

#include <bit>
#include <cmath>

#include "firmware/can/capture_channels.hpp"
#include "firmware/can/frame_codec.hpp"

namespace tnv::fw::can {
namespace {

// round(value / scale) as an i32, saturated; NaN -> 0.
std::uint32_t i32_word(double value, double scale) noexcept {
  const double raw = std::round(value / scale);
  if (!(raw == raw)) return 0;
  if (raw >= 2147483647.0) return 0x7FFFFFFFu;
  if (raw <= -2147483648.0) return 0x80000000u;
  return static_cast<std::uint32_t>(static_cast<std::int32_t>(raw));
}
std::uint32_t f32_word(double value) noexcept { return float_bits(static_cast<float>(value)); }

bool in_motion(const TickRecord& r) noexcept {
  return r.state == MotionState::dwell || r.state == MotionState::moving || r.motion_tick >= 0;
}

}  // namespace

std::uint32_t channel_word(std::uint8_t bit, const TickRecord& r, const TickSignals& sig) noexcept {
  const ChannelDef* c = find_channel(bit);
  if (c == nullptr) return 0;
  const AxisTickRecord& a = r.axis[c->axis];
  switch (c->kind) {
    case ChannelKind::position: return i32_word(a.position_mm, c->scale);
    case ChannelKind::reference: return i32_word(a.reference_mm, c->scale);
    case ChannelKind::speed: return f32_word(a.speed_mm_s);
    case ChannelKind::command: return f32_word(a.command_mm_s);
    case ChannelKind::sliding: return f32_word(a.s);
    case ChannelKind::d_hat: return f32_word(a.d_hat_mm_s);
    case ChannelKind::dac: return a.dac_code;
    case ChannelKind::force: return f32_word(sig.force_n);
    case ChannelKind::contour: return f32_word(sig.contour_um);
    case ChannelKind::motion_tick: return i32_word(static_cast<double>(r.motion_tick), 1.0);
    case ChannelKind::state: return static_cast<std::uint32_t>(r.state);
    case ChannelKind::unshaped: return i32_word(a.unshaped_reference_mm, c->scale);
    case ChannelKind::accel: return f32_word(a.accel_mm_s2);
    case ChannelKind::feed_override: return f32_word(r.feed_override);
    case ChannelKind::arsc_force_ref: return f32_word(r.arsc_force_ref_n);
    case ChannelKind::arsc_gain: return f32_word(r.arsc_cutting_gain_n_per_mm_s);
    case ChannelKind::excitation: return f32_word(a.excitation_mm_s);
  }
  return 0;
}

void CaptureRecorder::arm(const CaptureSettings& settings) noexcept {
  mask_ = channel_mask_of(settings.channels, settings.channels_high) & kAllCaptureChannels;
  channels_ = static_cast<std::uint32_t>(std::popcount(mask_));
  decimation_ = settings.decimation == 0 ? 1 : settings.decimation;
  trigger_ = settings.trigger;
  samples_ = 0;
  phase_ = 0;
  state_ = trigger_ == CaptureTrigger::immediate ? CaptureState::recording : CaptureState::armed;
}

void CaptureRecorder::abort() noexcept {
  if (state_ == CaptureState::armed || state_ == CaptureState::recording)
    state_ = samples_ > 0 ? CaptureState::done : CaptureState::idle;
}

void CaptureRecorder::record(const TickRecord& r, const TickSignals& sig) noexcept {
  std::uint32_t* out = buffer_.data() + static_cast<std::size_t>(samples_) * channels_;
  for (std::uint8_t bit = 0; bit < kCaptureChannels.size(); ++bit)
    if ((mask_ >> bit) & 1u) *out++ = channel_word(bit, r, sig);
  ++samples_;
  phase_ = 0;
}

void CaptureRecorder::on_tick(const TickRecord& r, const TickSignals& sig) noexcept {
  const MotionState before = last_state_;
  last_state_ = r.state;
  if (state_ == CaptureState::armed) {
    const bool fire = trigger_ == CaptureTrigger::motion  ? in_motion(r)
                      : trigger_ == CaptureTrigger::fault ? r.state == MotionState::faulted && before != MotionState::faulted
                                                          : true;
    if (!fire) return;
    state_ = CaptureState::recording;
    record(r, sig);  // the trigger tick is the first sample
  } else if (state_ == CaptureState::recording) {
    ++phase_;
    const bool motion_ended = trigger_ == CaptureTrigger::motion && r.state != MotionState::dwell &&
                              r.state != MotionState::moving;
    if (motion_ended || phase_ >= decimation_) record(r, sig);
    if (motion_ended) {
      state_ = CaptureState::done;
      return;
    }
  } else {
    return;
  }
  // The trigger tick of a motion that ends in that very tick also ends the capture.
  if (trigger_ == CaptureTrigger::motion && r.state != MotionState::dwell && r.state != MotionState::moving)
    state_ = CaptureState::done;
  if (samples_ >= capacity_samples()) state_ = CaptureState::done;
}

std::uint8_t CaptureRecorder::image_byte(std::uint32_t offset) const noexcept {
  if (offset >= image_bytes()) return 0;
  return static_cast<std::uint8_t>(buffer_[offset / 4] >> (8 * (offset % 4)));
}

}  // namespace tnv::fw::can
