#include "tools/protogen/bus_load.hpp"

namespace tnv::protogen {

namespace {

double rate_hz(std::uint32_t period_ms) noexcept { return period_ms == 0 ? 0.0 : 1000.0 / period_ms; }

}  // namespace

BusLoad telemetry_load(const fw::can::NodeSettings& s) noexcept {
  const auto& t = s.telemetry;
  // TLM_SLIDING is two frames (x and y) per period; every cyclic frame is 8 bytes.
  const double frames = rate_hz(t.heartbeat_ms) + rate_hz(t.position_ms) + rate_hz(t.following_ms) +
                        2.0 * rate_hz(t.sliding_ms) + rate_hz(t.output_ms) + rate_hz(t.contour_ms) +
                        rate_hz(t.arsc_ms) + rate_hz(t.spindle_ms);
  const double bit_rate = 1000.0 * s.can.bitrate_kbit;
  return {frames, frames * frame_bits_nominal(8) / bit_rate, frames * frame_bits_worst(8) / bit_rate};
}

double capture_upload_bytes_per_s(std::uint32_t bitrate_kbit) noexcept {
  return 7.0 * 1000.0 * bitrate_kbit / frame_bits_nominal(8);
}

}  // namespace tnv::protogen
