#pragma once
// Whether the node's live parameter set changed, for the can_frames
// invariants: the same bytes (padding included) are certainly the same
// set; on a difference the stored images decide (padding or a NaN's bits
// may differ where the parameters do not). It keeps the bytes and the image
// of the set seen last, so a look that finds the same bytes costs one
// compare, and an image is encoded once per change into a fixed buffer
// (encoding both sides of every frame, with a vector each, was a tenth of
// an input's time). A copy taken after a reset starts the next input
// without encoding the start set again.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

#include "firmware/can/node_settings.hpp"
#include "firmware/can/param_image.hpp"

namespace tnv::fuzz {

class SettingsWatch {
 public:
  // Takes `s` as the set now; true if its stored image differs from that
  // of the set seen by the previous look (false at the first look).
  bool look(const fw::can::NodeSettings& s) {
    if (seen_ && std::memcmp(bytes_.data(), static_cast<const void*>(&s), sizeof s) == 0) return false;
    std::memcpy(bytes_.data(), static_cast<const void*>(&s), sizeof s);
    static Image next;  // scratch, not part of what a copy carries
    const std::size_t size = fw::can::encode_image(s, next);
    const bool changed = seen_ && (size != size_ || std::memcmp(next.data(), image_.data(), size) != 0);
    std::memcpy(image_.data(), next.data(), size);
    size_ = size;
    seen_ = true;
    return changed;
  }

 private:
  using Image = std::array<std::uint8_t, fw::can::kParamImageMaxBytes>;
  bool seen_ = false;
  std::array<unsigned char, sizeof(fw::can::NodeSettings)> bytes_{};
  Image image_{};
  std::size_t size_ = 0;
};

}  // namespace tnv::fuzz
