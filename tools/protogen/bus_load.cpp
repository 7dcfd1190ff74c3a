#include "tools/protogen/bus_load.hpp"

#include "firmware/can/node_fields.hpp"

namespace tnv::protogen {

namespace {

double rate_hz(std::uint32_t period_ms) noexcept { return period_ms == 0 ? 0.0 : 1000.0 / period_ms; }

}  // namespace

BusLoad telemetry_load(const fw::can::NodeSettings& s) noexcept {
  namespace f = fw::can::fields;
  const auto& t = s.telemetry;
  BusLoad load;
  double bits_nominal = 0.0, bits_worst = 0.0;
  // `count` frames of `m` every `period_ms`.
  const auto add = [&](const fw::can::MessageDef& m, std::uint32_t period_ms, double count) {
    const double hz = count * rate_hz(period_ms);
    load.frames_per_s += hz;
    bits_nominal += hz * frame_bits_nominal(m.dlc);
    bits_worst += hz * frame_bits_worst(m.dlc);
  };
  const double axes = static_cast<double>(hal::kAxisCount);  // one frame per axis of a per-axis block
  add(f::kHeartbeatMsg, t.heartbeat_ms, 1.0);
  add(*f::kPositionMsgs[0], t.position_ms, axes);
  add(*f::kSlidingMsgs[0], t.sliding_ms, axes);
  add(*f::kDacMsgs[0], t.output_ms, axes);
  add(f::kOutputMsg, t.output_ms, 1.0);
  add(f::kContourMsg, t.contour_ms, 1.0);
  add(f::kArscMsg, t.arsc_ms, 1.0);
  add(f::kTlmSpindleMsg, t.spindle_ms, 1.0);
  const double bit_rate = 1000.0 * s.can.bitrate_kbit;
  load.load_nominal = bits_nominal / bit_rate;
  load.load_worst = bits_worst / bit_rate;
  return load;
}

double capture_upload_bytes_per_s(std::uint32_t bitrate_kbit) noexcept {
  return 7.0 * 1000.0 * bitrate_kbit / frame_bits_nominal(8);
}

}  // namespace tnv::protogen
