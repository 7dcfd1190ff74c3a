#pragma once
// Small helpers shared by the fuzz entries.
#include <cstdint>
#include <string>
#include <vector>

#include "firmware/can/node_settings.hpp"
#include "firmware/can/param_image.hpp"

namespace tnv::fuzz {

// The stored parameters of `s` as image bytes: equal images, equal sets.
inline std::vector<std::uint8_t> image_of(const fw::can::NodeSettings& s) {
  std::vector<std::uint8_t> out(fw::can::kParamImageMaxBytes);
  out.resize(fw::can::encode_image(s, out));
  return out;
}

inline std::string broken(const char* what, std::size_t at) {
  std::string s = what;
  s.append(" (input record ").append(std::to_string(at)).append(")");
  return s;
}

}  // namespace tnv::fuzz
