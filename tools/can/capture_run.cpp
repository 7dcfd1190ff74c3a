#include "tools/can/capture_run.hpp"

#include <bit>
#include <utility>
#include <vector>

#include "firmware/can/param_table.hpp"
#include "tools/can/param_text.hpp"

namespace tnv::can_host {

const char* capture_state_name(can::CaptureState s) {
  switch (s) {
    case can::CaptureState::idle: return "idle";
    case can::CaptureState::armed: return "armed";
    case can::CaptureState::recording: return "recording";
    case can::CaptureState::done: return "done";
  }
  return "?";
}

void check_capture_setup(const CaptureSetup& setup) {
  std::string error;
  if (!setup.channels.empty() && !parse_channel_list(setup.channels, error)) throw std::invalid_argument(error);
  if (!setup.trigger.empty() && !parse_param_value(*can::find_param("capture.trigger"), setup.trigger, error))
    throw std::invalid_argument(error);
  if (setup.decimation < 0 || setup.decimation > 255)
    throw std::invalid_argument("capture decimation must be 1..255 ticks per sample (0: the node's)");
}

can::ChannelMask read_channel_mask(NodeClient& client) {
  const auto low = static_cast<std::uint32_t>(client.get(*can::find_param("capture.channels")));
  const auto high = static_cast<std::uint32_t>(client.get(*can::find_param("capture.channels_high")));
  return can::channel_mask_of(low, high);
}

void stage_channel_mask(NodeClient& client, can::ChannelMask mask) {
  client.stage(*can::find_param("capture.channels"), can::channel_mask_low(mask));
  client.stage(*can::find_param("capture.channels_high"), can::channel_mask_high(mask));
}

ArmedCapture arm_capture(NodeClient& client, const CaptureSetup& setup) {
  check_capture_setup(setup);
  std::vector<std::pair<const can::ParamDef*, double>> changes;
  std::string error;
  if (!setup.channels.empty()) {
    const can::ChannelMask mask = *parse_channel_list(setup.channels, error);
    changes.emplace_back(can::find_param("capture.channels"), can::channel_mask_low(mask));
    changes.emplace_back(can::find_param("capture.channels_high"), can::channel_mask_high(mask));
  }
  if (!setup.trigger.empty()) {
    const can::ParamDef* p = can::find_param("capture.trigger");
    changes.emplace_back(p, *parse_param_value(*p, setup.trigger, error));
  }
  if (setup.decimation > 0) changes.emplace_back(can::find_param("capture.decimation"), setup.decimation);
  if (!changes.empty()) {
    for (const auto& [p, v] : changes) client.stage(*p, v);
    client.commit();
  }
  ArmedCapture armed;
  armed.channel_mask = read_channel_mask(client);
  const can::ParamDef& trigger = *can::find_param("capture.trigger");
  armed.trigger = format_param_value(trigger, client.get(trigger));
  armed.decimation = static_cast<int>(client.get(*can::find_param("capture.decimation")));
  armed.status = client.capture(can::CaptureOp::arm);
  return armed;
}

void stop_capture_after(NodeClient& client, Micros tail) {
  if (tail > Micros{0}) client.pump(tail);
  if (client.capture(can::CaptureOp::status).state != can::CaptureState::done) client.capture(can::CaptureOp::abort);
}

DownloadedCapture download_capture(NodeClient& client, Micros wait, const UploadProgress& progress) {
  CaptureStatus status = client.capture(can::CaptureOp::status);
  if (status.state != can::CaptureState::done) {
    if (wait <= Micros{0}) {
      std::string message = "capture not done (";
      throw CaptureError(message.append(capture_state_name(status.state)).append("); wait with --wait-s S"));
    }
    status = client.wait_capture_done(wait, Micros{100'000});
  }
  const can::ChannelMask mask = read_channel_mask(client);
  if (std::popcount(mask) != status.channels) {
    std::string message = "capture.channels was changed after the recording: the image cannot be decoded (";
    message.append(std::to_string(status.channels)).append(" channels recorded, the channel mask has ");
    throw CaptureError(message.append(std::to_string(std::popcount(mask))).append(")"));
  }
  const Micros started = client.bus().now();
  const std::uint64_t rerequests_before = client.upload_rerequests();
  const std::vector<std::uint8_t> image = client.upload(status, progress);
  DownloadedCapture out;
  out.upload_s = static_cast<double>((client.bus().now() - started).count()) * 1e-6;
  std::string error;
  auto table = decode_capture(image, mask, status.samples, status.decimation, error);
  if (!table) throw CaptureError(error);
  out.table = std::move(*table);
  out.status = status;
  out.channel_mask = mask;
  out.bytes = image.size();
  out.rerequests = client.upload_rerequests() - rerequests_before;
  return out;
}

}  // namespace tnv::can_host
