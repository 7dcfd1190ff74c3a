#pragma once
// JOG, MOVE and CIRCLE: the motion requests a host sends besides COMMAND
// and a program, each answered by one COMMAND_ACK (detail = index of the
// offending field). Each needs command ownership; every check comes before
// anything is started: a refused request changes nothing. The ramps and
// dwells of a move and a circle are the live motion.* parameters.
// Bounded work, no allocation, exceptions, locks or logging: it runs in
// CanNode::service().
#include "firmware/can/command_ack.hpp"
#include "firmware/can/host_access.hpp"
#include "firmware/can/motion_acceptance.hpp"
#include "firmware/can/node_parameters.hpp"
#include "firmware/tick/tick_task.hpp"
#include "hal/can_port.hpp"

namespace tnv::fw::can {

class MotionRequests {
 public:
  MotionRequests(TickTask& task, const HostAccess& access, CommandAck& ack, const NodeParameters& params,
                 MotionAcceptance& motion) noexcept
      : task_(task), access_(access), ack_(ack), params_(params), motion_(motion) {}
  MotionRequests(const MotionRequests&) = delete;
  MotionRequests& operator=(const MotionRequests&) = delete;

  // Each the message of the request being handled, answered here.
  void jog(const hal::CanFrame& frame) noexcept;
  void move(const hal::CanFrame& frame) noexcept;
  void circle(const hal::CanFrame& frame) noexcept;

 private:
  TickTask& task_;
  const HostAccess& access_;
  CommandAck& ack_;
  const NodeParameters& params_;
  MotionAcceptance& motion_;
};

}  // namespace tnv::fw::can
