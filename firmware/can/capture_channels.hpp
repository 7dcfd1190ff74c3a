#pragma once
// THE protocol table, part 3: what an on-target capture can record. Each
// channel is one 32-bit little-endian value per sample; bit n of the
// capture.channels parameter selects channel n, and a sample holds the
// selected channels in bit order.
#include <array>
#include <cstdint>

#include "firmware/can/wire.hpp"

namespace tnv::fw::can {

struct ChannelDef {
  std::uint8_t bit;
  const char* name;
  WireType type;  // i32, u32 or f32
  double scale;   // physical = raw * scale
  const char* unit;
  const char* doc;
};

inline constexpr std::array<ChannelDef, 27> kCaptureChannels{{
    {0, "pos_x", WireType::i32, 1e-6, "mm", "encoder position, x"},
    {1, "pos_y", WireType::i32, 1e-6, "mm", "encoder position, y"},
    {2, "ref_x", WireType::i32, 1e-6, "mm", "reference the loop follows (after the shaper), x"},
    {3, "ref_y", WireType::i32, 1e-6, "mm", "reference the loop follows (after the shaper), y"},
    {4, "speed_x", WireType::f32, 1, "mm/s", "M-method speed, x"},
    {5, "speed_y", WireType::f32, 1, "mm/s", "M-method speed, y"},
    {6, "command_x", WireType::f32, 1, "mm/s", "speed command u_k (controller output, plus a closed-loop excitation), x"},
    {7, "command_y", WireType::f32, 1, "mm/s", "speed command u_k (controller output, plus a closed-loop excitation), y"},
    {8, "s_x", WireType::f32, 1, "mm/s", "sliding variable s_k, x"},
    {9, "s_y", WireType::f32, 1, "mm/s", "sliding variable s_k, y"},
    {10, "d_hat_x", WireType::f32, 1, "mm/s", "disturbance estimate d^_k, x"},
    {11, "d_hat_y", WireType::f32, 1, "mm/s", "disturbance estimate d^_k, y"},
    {12, "dac_x", WireType::u32, 1, "", "DAC code, x"},
    {13, "dac_y", WireType::u32, 1, "", "DAC code, y"},
    {14, "force", WireType::f32, 1, "N", "force sensor"},
    {15, "contour", WireType::f32, 1, "um", "contour error of the running circle (S1 eq. 33)"},
    {16, "motion_tick", WireType::i32, 1, "tick", "ticks since the start of motion, -1 outside"},
    {17, "state", WireType::u32, 1, "", "motion state (0 disabled 1 dwell 2 moving 3 holding 4 faulted)"},
    {18, "unshaped_x", WireType::i32, 1e-6, "mm", "reference before the input shaper, x"},
    {19, "unshaped_y", WireType::i32, 1e-6, "mm", "reference before the input shaper, y"},
    {20, "accel_x", WireType::f32, 1, "mm/s2", "tool-side accelerometer, x (ADC_ACCEL_X)"},
    {21, "accel_y", WireType::f32, 1, "mm/s2", "tool-side accelerometer, y (ADC_ACCEL_Y)"},
    {22, "feed_override", WireType::f32, 1, "", "feed override of the motion core (the force loop's when arsc.enable)"},
    {23, "arsc_force_ref", WireType::f32, 1, "N", "the force loop's reference now (soft start included), 0 when off"},
    {24, "arsc_gain", WireType::f32, 1, "N*s/mm", "the force loop's cutting-gain estimate, 0 when off"},
    {25, "excite_x", WireType::f32, 1, "mm/s", "excitation d_k of EXCITE: added to command_x (sweep, multisine) or all of it (step, ramp, multisine_open); 0 otherwise"},
    {26, "excite_y", WireType::f32, 1, "mm/s", "excitation d_k of EXCITE: added to command_y (sweep, multisine) or all of it (step, ramp, multisine_open); 0 otherwise"},
}};

// The default set: enough to score a circle and plot the tracking.
inline constexpr std::uint32_t kDefaultCaptureChannels =
    (1u << 0) | (1u << 1) | (1u << 2) | (1u << 3) | (1u << 15) | (1u << 16);

constexpr std::uint32_t kAllCaptureChannels = (1u << kCaptureChannels.size()) - 1u;

constexpr const ChannelDef* find_channel(std::uint8_t bit) noexcept {
  for (const ChannelDef& c : kCaptureChannels)
    if (c.bit == bit) return &c;
  return nullptr;
}

}  // namespace tnv::fw::can
