#pragma once
// Small helpers shared by the fuzz entries.
#include <cstdint>
#include <string>
#include <vector>

#include "firmware/can/node_settings.hpp"
#include "firmware/can/param_image.hpp"
#include "hal/can_port.hpp"

namespace tnv::fuzz {

// The stored parameters of `s` as image bytes: equal images, equal sets.
inline std::vector<std::uint8_t> image_of(const fw::can::NodeSettings& s) {
  std::vector<std::uint8_t> out(fw::can::kParamImageMaxBytes);
  out.resize(fw::can::encode_image(s, out));
  return out;
}

// can_frames / frame_codec record: flags (bit 0 extended), id u16 LE, dlc
// (mod 9), 8 data bytes.
inline constexpr std::size_t kFrameRecordBytes = 12;

inline hal::CanFrame frame_of_record(const std::uint8_t* rec) {
  hal::CanFrame frame;
  frame.extended = (rec[0] & 1u) != 0;
  frame.id = static_cast<std::uint32_t>(rec[1] | rec[2] << 8) & (frame.extended ? 0xFFFFu : 0x7FFu);
  frame.dlc = static_cast<std::uint8_t>(rec[3] % 9u);
  for (std::size_t i = 0; i < 8; ++i) frame.data[i] = rec[4 + i];
  return frame;
}

inline std::string broken(const char* what, std::size_t at) {
  std::string s = what;
  s.append(" (input record ").append(std::to_string(at)).append(")");
  return s;
}

}  // namespace tnv::fuzz
