#pragma once
// SPINDLE (docs/safety.md "Spindle"), answered by one COMMAND_ACK (code =
// op, detail = index of the offending field). Like every command that
// moves the machine it needs command ownership, and every check comes
// before anything changes: a refusal changes nothing. During a program
// only a stop is taken (the program's elements command the spindle).
// Bounded work, no allocation, exceptions, locks or logging: it runs in
// CanNode::service().
#include "firmware/can/command_ack.hpp"
#include "firmware/can/host_access.hpp"
#include "firmware/can/motion_acceptance.hpp"
#include "firmware/can/program_stream.hpp"
#include "firmware/tick/tick_task.hpp"
#include "hal/can_port.hpp"

namespace tnv::fw::can {

class SpindleRequest {
 public:
  SpindleRequest(TickTask& task, const HostAccess& access, CommandAck& ack, const ProgramStream& programs,
                 MotionAcceptance& motion) noexcept
      : task_(task), access_(access), ack_(ack), programs_(programs), motion_(motion) {}
  SpindleRequest(const SpindleRequest&) = delete;
  SpindleRequest& operator=(const SpindleRequest&) = delete;

  // The SPINDLE of the request being handled, answered here.
  void handle(const hal::CanFrame& frame) noexcept;

 private:
  TickTask& task_;
  const HostAccess& access_;
  CommandAck& ack_;
  const ProgramStream& programs_;
  MotionAcceptance& motion_;
};

}  // namespace tnv::fw::can
