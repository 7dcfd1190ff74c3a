#pragma once
// COMMAND_ACK, the one answer to COMMAND, JOG, MOVE, CIRCLE, SHAPER, EXCITE,
// SEGMENT and SEGMENT_TAIL: the request's tag, its result and detail (the
// index of the offending field), and the node's state, fault and command
// owner as they are when it is sent. Counted and queued by NodeTransmit.
#include <cstdint>

#include "firmware/can/host_access.hpp"
#include "firmware/can/node_transmit.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "firmware/tick/tick_task.hpp"

namespace tnv::fw::can {

class CommandAck {
 public:
  CommandAck(std::uint8_t node_id, const TickTask& task, const HostAccess& access, NodeTransmit& tx) noexcept
      : node_id_(node_id), task_(task), access_(access), tx_(tx) {}

  // The answer to the request being handled (its tag: HostAccess::tag()).
  void send(std::uint8_t request, std::uint8_t code, ErrorCode result, std::uint8_t detail) noexcept {
    send_tagged(access_.tag(), request, code, result, detail);
  }
  // The answer to a request kept from before, echoing its `tag`.
  void send_tagged(std::uint8_t tag, std::uint8_t request, std::uint8_t code, ErrorCode result,
                   std::uint8_t detail) noexcept;

 private:
  std::uint8_t node_id_;
  const TickTask& task_;
  const HostAccess& access_;
  NodeTransmit& tx_;
};

}  // namespace tnv::fw::can
