// NodeCapture: CAPTURE_CONTROL, CAPTURE_STATUS and the CAPTURE_DATA upload.
#include "firmware/can/node_capture.hpp"

#include <algorithm>
#include <array>

#include "firmware/can/capture_channels.hpp"
#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"
#include "firmware/can/tick_signals.hpp"

namespace tnv::fw::can {

using namespace fields;

namespace {
constexpr std::uint32_t kDataBytesPerFrame = 7;
}

void NodeCapture::on_tick(const NodeSettings& settings) noexcept {
  capture_.on_tick(task_.last_record(), tick_signals(task_, settings));
  if (excite_capture_ && !task_.exciting()) {
    // The excitation's last tick (or the one that cancelled it) is recorded: the capture is done.
    excite_capture_ = false;
    capture_.abort();
  }
}

void NodeCapture::control(const hal::CanFrame& frame, const CaptureSettings& settings) noexcept {
  const auto op_raw = static_cast<std::uint8_t>(read_raw(frame, kCaptureOp));
  if (op_raw >= kCaptureOpCount) return reply(ErrorCode::unknown_command);
  const CaptureState st = capture_.state();
  switch (static_cast<CaptureOp>(op_raw)) {
    case CaptureOp::arm:
      if (st == CaptureState::recording || upload_.active) return reply(ErrorCode::busy);
      if ((channel_mask_of(settings.channels, settings.channels_high) & kAllCaptureChannels) == 0)
        return reply(ErrorCode::out_of_range);  // nothing to record
      capture_.arm(settings);
      excite_capture_ = false;
      return reply(ErrorCode::ok);
    case CaptureOp::abort:
      capture_.abort();
      excite_capture_ = false;
      upload_ = {};
      return reply(ErrorCode::ok);
    case CaptureOp::status: return reply(ErrorCode::ok);
    case CaptureOp::upload: {
      const auto frames = static_cast<std::uint16_t>(read_raw(frame, kCaptureFrames));
      const std::uint32_t offset = read_raw(frame, kCaptureOffset);
      if (st == CaptureState::recording || upload_.active) return reply(ErrorCode::busy);
      if (frames == 0) return reply(ErrorCode::out_of_range);
      if (st != CaptureState::done || offset >= capture_.image_bytes()) return reply(ErrorCode::not_ready);
      upload_ = {true, offset, frames, 0};  // answered by the data frames
      return;
    }
  }
}

void NodeCapture::reply(ErrorCode result) noexcept {
  hal::CanFrame frame = make_frame(kCaptureStatusMsg, node_id_);
  write_raw(frame, kStatusTag, access_.tag());
  write_raw(frame, kStatusState, static_cast<std::uint32_t>(capture_.state()));
  write_raw(frame, kStatusResult, static_cast<std::uint32_t>(result));
  write_raw(frame, kStatusChannels, capture_.channel_count());
  write_raw(frame, kStatusDecimation, std::min<std::uint32_t>(capture_.decimation(), 255u));
  write_raw(frame, kStatusSamples, std::min<std::uint32_t>(capture_.samples(), 0xFFFFFFu));
  tx_.answer(frame, result);
}

void NodeCapture::excitation_started(const CaptureSettings& settings) noexcept {
  if (capture_.state() != CaptureState::armed || settings.trigger != CaptureTrigger::motion) return;
  CaptureSettings now = settings;
  now.trigger = CaptureTrigger::immediate;
  capture_.arm(now);
  excite_capture_ = true;
}

// Lowest priority of all: a data frame goes out only when nothing else waits,
// and waits (is not lost) while the port is full.
void NodeCapture::send_upload() noexcept {
  while (upload_.active && tx_.idle()) {
    hal::CanFrame frame = make_frame(kCaptureDataMsg, node_id_);
    write_raw(frame, kDataSequence, upload_.next);
    std::array<std::uint8_t, kDataBytesPerFrame> bytes{};
    const std::uint32_t first = upload_.offset_bytes + upload_.next * kDataBytesPerFrame;
    for (std::uint32_t i = 0; i < kDataBytesPerFrame; ++i) bytes[i] = capture_.image_byte(first + i);  // 0 past the end
    write_bytes(frame, kDataBytes, bytes);
    if (!tx_.send_now(frame)) return;  // the queue is full: the rest goes next service()
    if (++upload_.next == upload_.frames) upload_ = {};
  }
}

bool NodeCapture::settings_locked() const noexcept {
  const CaptureState st = capture_.state();
  return st == CaptureState::armed || st == CaptureState::recording;
}

}  // namespace tnv::fw::can
