#include "firmware/can/node_settings.hpp"

#include "firmware/can/capture_channels.hpp"

namespace tnv::fw::can {

NodeSettings default_node_settings() noexcept {
  NodeSettings s;
  s.firmware = default_firmware_config();
  s.capture.channels = channel_mask_low(kDefaultCaptureChannels);
  s.capture.channels_high = channel_mask_high(kDefaultCaptureChannels);
  return s;
}

const NodeSettings& cached_default_node_settings() noexcept {
  static const NodeSettings defaults = default_node_settings();
  return defaults;
}

}  // namespace tnv::fw::can
