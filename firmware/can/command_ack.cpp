// CommandAck: the COMMAND_ACK frame.
#include "firmware/can/command_ack.hpp"

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"

namespace tnv::fw::can {

using namespace fields;

void CommandAck::send_tagged(std::uint8_t tag, std::uint8_t request, std::uint8_t code, ErrorCode result,
                             std::uint8_t detail) noexcept {
  hal::CanFrame frame = make_frame(kAckMsg, node_id_);
  write_raw(frame, kAckTag, tag);
  write_raw(frame, kAckRequest, request);
  write_raw(frame, kAckCode, code);
  write_raw(frame, kAckResult, static_cast<std::uint32_t>(result));
  write_raw(frame, kAckState, static_cast<std::uint32_t>(task_.state()));
  write_raw(frame, kAckFault, static_cast<std::uint32_t>(task_.fault().reason));
  write_raw(frame, kAckDetail, detail);
  write_raw(frame, kAckOwner, access_.owner());
  tx_.answer(frame, result);
}

}  // namespace tnv::fw::can
