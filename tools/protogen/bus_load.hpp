#pragma once
// Bus time of classic CAN frames and the load of the cyclic messages.
#include <cstdint>

#include "firmware/can/node_settings.hpp"

namespace tnv::protogen {

// Bits on the wire of a classic data frame with an 11-bit identifier and
// `data_bytes` bytes, including the 3-bit interframe space: 47 + 8 n
// without stuff bits; with the worst case of stuffing (one stuff bit per 4
// bits of the 34 + 8 n stuffed bits) it is up to (34 + 8 n - 1) / 4 more.
constexpr int frame_bits_nominal(int data_bytes) noexcept { return 47 + 8 * data_bytes; }
constexpr int frame_bits_worst(int data_bytes) noexcept {
  return frame_bits_nominal(data_bytes) + (34 + 8 * data_bytes - 1) / 4;
}

struct BusLoad {
  double frames_per_s = 0.0;
  double load_nominal = 0.0;  // fraction of the bit rate, no stuff bits
  double load_worst = 0.0;    // with worst-case stuffing
};

// The cyclic messages of `settings` (heartbeat + telemetry) on a bus of bitrate_kbit.
BusLoad telemetry_load(const fw::can::NodeSettings& settings) noexcept;

// Capture upload: bytes of image per second at bitrate_kbit (7 bytes per 8-byte frame).
double capture_upload_bytes_per_s(std::uint32_t bitrate_kbit) noexcept;

}  // namespace tnv::protogen
