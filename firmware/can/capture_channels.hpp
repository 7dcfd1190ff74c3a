#pragma once
// THE protocol table, part 3: what an on-target capture can record. Each
// channel is one 32-bit little-endian value per sample; bit n of the 64-bit
// channel mask selects channel n (capture.channels holds bits 0-31,
// capture.channels_high bits 32-63), and a sample holds the selected
// channels in bit order. A channel's bit is its place in the list
// below; a per-axis channel is one per axis of TNV_AXES (hal/axis.hpp), in
// axis order ("pos_x", "pos_y").
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "firmware/can/wire.hpp"
#include "hal/axis.hpp"

namespace tnv::fw::can {

// What a channel records (capture_recorder.cpp reads it from the tick's record).
enum class ChannelKind : std::uint8_t {
  position,
  reference,
  speed,
  command,
  sliding,
  d_hat,
  dac,
  force,
  contour,
  motion_tick,
  state,
  unshaped,
  accel,
  feed_override,
  arsc_force_ref,
  arsc_gain,
  excitation,
};

struct ChannelDef {
  std::uint8_t bit;
  const char* name;
  WireType type;  // i32, u32 or f32
  double scale;   // physical = raw * scale
  const char* unit;
  const char* doc;
  ChannelKind kind;
  std::uint8_t axis;  // the axis' index for a per-axis channel, else 0
};

namespace detail {

// Per-axis rows: X-macros over the axis list, one per kind.
#define TNV_CH_POS(a, ...) {0, "pos_" #a, WireType::i32, 1e-6, "mm", "encoder position, " #a, ChannelKind::position, static_cast<std::uint8_t>(hal::Axis::a)},
#define TNV_CH_REF(a, ...) {0, "ref_" #a, WireType::i32, 1e-6, "mm", "reference the loop follows (after the shaper), " #a, ChannelKind::reference, static_cast<std::uint8_t>(hal::Axis::a)},
#define TNV_CH_SPEED(a, ...) {0, "speed_" #a, WireType::f32, 1, "mm/s", "M-method speed, " #a, ChannelKind::speed, static_cast<std::uint8_t>(hal::Axis::a)},
#define TNV_CH_COMMAND(a, ...) {0, "command_" #a, WireType::f32, 1, "mm/s", "speed command u_k (controller output, plus a closed-loop excitation), " #a, ChannelKind::command, static_cast<std::uint8_t>(hal::Axis::a)},
#define TNV_CH_S(a, ...) {0, "s_" #a, WireType::f32, 1, "mm/s", "sliding variable s_k, " #a, ChannelKind::sliding, static_cast<std::uint8_t>(hal::Axis::a)},
#define TNV_CH_DHAT(a, ...) {0, "d_hat_" #a, WireType::f32, 1, "mm/s", "disturbance estimate d^_k, " #a, ChannelKind::d_hat, static_cast<std::uint8_t>(hal::Axis::a)},
#define TNV_CH_DAC(a, ...) {0, "dac_" #a, WireType::u32, 1, "", "DAC code, " #a, ChannelKind::dac, static_cast<std::uint8_t>(hal::Axis::a)},
#define TNV_CH_UNSHAPED(a, ...) {0, "unshaped_" #a, WireType::i32, 1e-6, "mm", "reference before the input shaper, " #a, ChannelKind::unshaped, static_cast<std::uint8_t>(hal::Axis::a)},
#define TNV_CH_ACCEL(a, ...) {0, "accel_" #a, WireType::f32, 1, "mm/s2", "tool-side accelerometer, " #a " (ADC_ACCEL_" #a ")", ChannelKind::accel, static_cast<std::uint8_t>(hal::Axis::a)},
#define TNV_CH_EXCITE(a, ...) {0, "excite_" #a, WireType::f32, 1, "mm/s", "excitation d_k of EXCITE: added to command_" #a " (sweep, multisine) or all of it (step, ramp, multisine_open); 0 otherwise", ChannelKind::excitation, static_cast<std::uint8_t>(hal::Axis::a)},

inline constexpr ChannelDef kChannelRows[] = {
    TNV_AXES(TNV_CH_POS)
    TNV_AXES(TNV_CH_REF)
    TNV_AXES(TNV_CH_SPEED)
    TNV_AXES(TNV_CH_COMMAND)
    TNV_AXES(TNV_CH_S)
    TNV_AXES(TNV_CH_DHAT)
    TNV_AXES(TNV_CH_DAC)
    {0, "force", WireType::f32, 1, "N", "force sensor", ChannelKind::force, 0},
    {0, "contour", WireType::f32, 1, "um", "contour error of the running circle (S1 eq. 33)", ChannelKind::contour, 0},
    {0, "motion_tick", WireType::i32, 1, "tick", "ticks since the start of motion, -1 outside", ChannelKind::motion_tick, 0},
    {0, "state", WireType::u32, 1, "", "motion state (0 disabled 1 dwell 2 moving 3 holding 4 faulted)", ChannelKind::state, 0},
    TNV_AXES(TNV_CH_UNSHAPED)
    TNV_AXES(TNV_CH_ACCEL)
    {0, "feed_override", WireType::f32, 1, "", "feed override of the motion core (the force loop's when arsc.enable)", ChannelKind::feed_override, 0},
    {0, "arsc_force_ref", WireType::f32, 1, "N", "the force loop's reference now (soft start included), 0 when off", ChannelKind::arsc_force_ref, 0},
    {0, "arsc_gain", WireType::f32, 1, "N*s/mm", "the force loop's cutting-gain estimate, 0 when off", ChannelKind::arsc_gain, 0},
    TNV_AXES(TNV_CH_EXCITE)
};

#undef TNV_CH_POS
#undef TNV_CH_REF
#undef TNV_CH_SPEED
#undef TNV_CH_COMMAND
#undef TNV_CH_S
#undef TNV_CH_DHAT
#undef TNV_CH_DAC
#undef TNV_CH_UNSHAPED
#undef TNV_CH_ACCEL
#undef TNV_CH_EXCITE

inline constexpr std::size_t kChannelCount = std::size(kChannelRows);

constexpr std::array<ChannelDef, kChannelCount> numbered_channels() {
  std::array<ChannelDef, kChannelCount> out{};
  for (std::size_t i = 0; i < kChannelCount; ++i) {
    out[i] = kChannelRows[i];
    out[i].bit = static_cast<std::uint8_t>(i);
  }
  return out;
}

}  // namespace detail

// The channel mask: 64 bits, in two 32-bit parameters (capture.channels,
// capture.channels_high).
using ChannelMask = std::uint64_t;
static_assert(detail::kChannelCount <= 64, "capture channels: at most 64 (capture.channels and capture.channels_high)");
constexpr ChannelMask channel_mask_bit(std::uint8_t bit) noexcept { return ChannelMask{1} << bit; }
constexpr std::uint32_t channel_mask_low(ChannelMask m) noexcept { return static_cast<std::uint32_t>(m); }
constexpr std::uint32_t channel_mask_high(ChannelMask m) noexcept { return static_cast<std::uint32_t>(m >> 32); }
constexpr ChannelMask channel_mask_of(std::uint32_t low, std::uint32_t high) noexcept {
  return ChannelMask{low} | ChannelMask{high} << 32;
}

inline constexpr std::array<ChannelDef, detail::kChannelCount> kCaptureChannels = detail::numbered_channels();

constexpr const ChannelDef* find_channel(std::uint8_t bit) noexcept {
  return bit < kCaptureChannels.size() ? &kCaptureChannels[bit] : nullptr;
}

// A channel's bit by name; a typo fails the build.
consteval std::uint8_t channel_bit(std::string_view name) {
  for (const ChannelDef& c : kCaptureChannels)
    if (name == c.name) return c.bit;
  detail::no_such_field_in_this_message();
  return 0;
}

// The default set: enough to score a circle and plot the tracking (the XY
// plane's positions and references, the contour error, the motion tick).
inline constexpr ChannelMask kDefaultCaptureChannels =
    channel_mask_bit(channel_bit("pos_x")) | channel_mask_bit(channel_bit("pos_y")) |
    channel_mask_bit(channel_bit("ref_x")) | channel_mask_bit(channel_bit("ref_y")) |
    channel_mask_bit(channel_bit("contour")) | channel_mask_bit(channel_bit("motion_tick"));

constexpr ChannelMask kAllCaptureChannels =
    kCaptureChannels.size() == 64 ? ~ChannelMask{0} : (ChannelMask{1} << kCaptureChannels.size()) - 1u;

}  // namespace tnv::fw::can
