#pragma once
// What every accepted motion request does besides starting the motion
// (COMMAND home, JOG, MOVE, CIRCLE, EXCITE, SPINDLE, SEGMENT): the node
// leaves commissioning mode and the heartbeat's sticky jog-deadman and
// host-timeout bits clear. One place for the rule, used by every part that
// accepts motion.
#include "firmware/can/commissioning_mode.hpp"
#include "firmware/can/node_telemetry.hpp"

namespace tnv::fw::can {

class MotionAcceptance {
 public:
  MotionAcceptance(CommissioningMode& commissioning, NodeTelemetry& telemetry) noexcept
      : commissioning_(commissioning), telemetry_(telemetry) {}

  void accepted() noexcept {
    commissioning_.leave();
    telemetry_.motion_accepted();
  }

 private:
  CommissioningMode& commissioning_;
  NodeTelemetry& telemetry_;
};

}  // namespace tnv::fw::can
