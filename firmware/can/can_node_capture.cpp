// CanNode: CAPTURE_CONTROL (arm / abort / status / upload) and the
// segmented upload, CAPTURE_DATA frames sent over as many service() calls
// as the transmit queue needs.
#include <array>

#include "firmware/can/can_node.hpp"
#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"

namespace tnv::fw::can {

using namespace fields;

namespace {
constexpr std::uint32_t kDataBytesPerFrame = 7;
}

void CanNode::handle_capture(const hal::CanFrame& frame) noexcept {
  const auto op_raw = static_cast<std::uint8_t>(read_raw(frame, kCaptureOp));
  if (op_raw >= kCaptureOpCount) return reply_capture(ErrorCode::unknown_command);
  const CaptureState st = capture_.state();
  switch (static_cast<CaptureOp>(op_raw)) {
    case CaptureOp::arm:
      if (st == CaptureState::recording || upload_.active) return reply_capture(ErrorCode::busy);
      capture_.arm(settings_.capture);
      excite_capture_ = false;
      return reply_capture(ErrorCode::ok);
    case CaptureOp::abort:
      capture_.abort();
      excite_capture_ = false;
      upload_ = {};
      return reply_capture(ErrorCode::ok);
    case CaptureOp::status: return reply_capture(ErrorCode::ok);
    case CaptureOp::upload: {
      const auto frames = static_cast<std::uint16_t>(read_raw(frame, kCaptureFrames));
      const std::uint32_t offset = read_raw(frame, kCaptureOffset);
      if (st == CaptureState::recording || upload_.active) return reply_capture(ErrorCode::busy);
      if (frames == 0) return reply_capture(ErrorCode::out_of_range);
      if (st != CaptureState::done || offset >= capture_.image_bytes()) return reply_capture(ErrorCode::not_ready);
      upload_ = {true, offset, frames, 0};  // answered by the data frames
      return;
    }
  }
}

// Lowest priority of all: a data frame goes out only when nothing else waits,
// and waits (is not lost) while the port is full.
void CanNode::send_upload() noexcept {
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

}  // namespace tnv::fw::can
