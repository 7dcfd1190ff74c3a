#pragma once
// A downloaded capture as named columns of physical values
// (firmware/can/capture_channels.hpp): the image is samples x channels
// 32-bit little-endian values, sample-major, channels in bit order.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "firmware/can/capture_channels.hpp"

namespace tnv::can_host {

namespace can = tnv::fw::can;

struct CaptureTable {
  std::uint32_t decimation = 1;  // ticks per sample
  std::vector<const can::ChannelDef*> channels;
  std::vector<std::vector<double>> columns;  // one per channel, physical units

  std::size_t samples() const noexcept { return columns.empty() ? 0 : columns.front().size(); }
  // The column of a channel by name; nullptr when it was not captured.
  const std::vector<double>* column(std::string_view name) const noexcept;
  double period_s() const noexcept { return decimation * 1e-3; }
};

// nullopt with `error` when the image length is not samples x channels x 4.
std::optional<CaptureTable> decode_capture(std::span<const std::uint8_t> image, can::ChannelMask channel_mask,
                                           std::uint32_t samples, std::uint32_t decimation, std::string& error);

// "pos_x,pos_y,contour" -> mask; also "default" and "all". nullopt with
// `error` naming the unknown channel and listing the valid ones.
std::optional<can::ChannelMask> parse_channel_list(const std::string& list, std::string& error);
std::string channel_list_text(can::ChannelMask mask);

// CSV / JSON column name with the unit: pos_x_mm, speed_x_mm_s, contour_um, motion_tick.
std::string column_name(const can::ChannelDef& c);

}  // namespace tnv::can_host
