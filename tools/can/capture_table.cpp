#include "tools/can/capture_table.hpp"

#include <bit>
#include <cstring>
#include <sstream>

namespace tnv::can_host {

const std::vector<double>* CaptureTable::column(std::string_view name) const noexcept {
  for (std::size_t i = 0; i < channels.size(); ++i)
    if (name == channels[i]->name) return &columns[i];
  return nullptr;
}

namespace {

double physical(const can::ChannelDef& c, std::uint32_t raw) {
  switch (c.type) {
    case can::WireType::i32: return static_cast<double>(static_cast<std::int32_t>(raw)) * c.scale;
    case can::WireType::f32: return static_cast<double>(std::bit_cast<float>(raw));
    default: return static_cast<double>(raw) * c.scale;
  }
}

}  // namespace

std::optional<CaptureTable> decode_capture(std::span<const std::uint8_t> image, can::ChannelMask channel_mask,
                                           std::uint32_t samples, std::uint32_t decimation, std::string& error) {
  CaptureTable t;
  t.decimation = decimation;
  for (const can::ChannelDef& c : can::kCaptureChannels)
    if ((channel_mask >> c.bit) & 1u) t.channels.push_back(&c);
  const std::size_t n = t.channels.size();
  const std::uint64_t expected = static_cast<std::uint64_t>(samples) * n * 4u;
  if (image.size() != expected || (channel_mask & ~can::kAllCaptureChannels) != 0) {
    error = "capture image of ";
    error.append(std::to_string(image.size())).append(" bytes does not hold ").append(std::to_string(samples));
    error.append(" samples of ").append(std::to_string(n)).append(" channels");
    return std::nullopt;
  }
  t.columns.assign(n, std::vector<double>(samples));
  std::size_t at = 0;
  for (std::uint32_t s = 0; s < samples; ++s) {
    for (std::size_t c = 0; c < n; ++c, at += 4) {
      const std::uint32_t raw = static_cast<std::uint32_t>(image[at]) | static_cast<std::uint32_t>(image[at + 1]) << 8 |
                                static_cast<std::uint32_t>(image[at + 2]) << 16 |
                                static_cast<std::uint32_t>(image[at + 3]) << 24;
      t.columns[c][s] = physical(*t.channels[c], raw);
    }
  }
  return t;
}

std::optional<can::ChannelMask> parse_channel_list(const std::string& list, std::string& error) {
  if (list == "default") return can::kDefaultCaptureChannels;
  if (list == "all") return can::kAllCaptureChannels;
  can::ChannelMask mask = 0;
  std::istringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    if (name.empty()) continue;
    const can::ChannelDef* found = nullptr;
    for (const can::ChannelDef& c : can::kCaptureChannels)
      if (name == c.name) found = &c;
    if (found == nullptr) {
      error = "unknown capture channel '";
      error.append(name).append("' (channels: ").append(channel_list_text(can::kAllCaptureChannels)).append(")");
      return std::nullopt;
    }
    mask |= can::channel_mask_bit(found->bit);
  }
  if (mask == 0) {
    error = "no capture channels given";
    return std::nullopt;
  }
  return mask;
}

std::string channel_list_text(can::ChannelMask mask) {
  std::string out;
  for (const can::ChannelDef& c : can::kCaptureChannels)
    if ((mask >> c.bit) & 1u) {
      if (!out.empty()) out += ',';
      out += c.name;
    }
  return out;
}

std::string column_name(const can::ChannelDef& c) {
  std::string out = c.name;
  if (c.unit[0] == '\0' || std::strcmp(c.unit, "tick") == 0) return out;
  out += '_';
  for (const char* u = c.unit; *u != '\0'; ++u) out += *u == '/' ? '_' : *u;
  return out;
}

}  // namespace tnv::can_host
