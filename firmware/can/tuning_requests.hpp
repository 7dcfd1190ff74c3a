#pragma once
// SHAPER and EXCITE: the tuning requests, each answered by one COMMAND_ACK
// (detail = index of the offending field). Each needs command ownership;
// every check comes first, a refused request changes nothing.
//
// SHAPER is the same as staging <axis>.shaper.type / freq_hz / zeta and
// committing (NodeParameters::apply(); a design the node lacks defers it,
// ShaperDesignDeferral). EXCITE is the open-loop excitation for
// identification and the sweep / multisine (closed loop) and
// multisine_open for frequency response (TickTask::start_excitation,
// docs/autotune.md, docs/frequency-response.md). Its frame carries axis,
// kind, duration and level; the ramp rate, the settle time and the
// breakaway count are ExcitationSpec's defaults (2 mm/s^2, 0.2 s, 12
// counts), the values of the host's identification sequence
// (tools/hil/tune_sequence.hpp); the band and tone count of a sweep /
// multisine are the excite.* parameters (validated when set), and so is a
// sweep / multisine's carrier (excite.carrier_mm_s), whose travel, carrier
// x duration from where the axis stands, must end inside the soft limits
// (else out_of_range on the duration field). A capture armed for a motion
// records an accepted EXCITE (NodeCapture).
//
// Bounded work, no allocation, exceptions, locks or logging: it runs in
// CanNode::service().
#include "firmware/can/command_ack.hpp"
#include "firmware/can/host_access.hpp"
#include "firmware/can/motion_acceptance.hpp"
#include "firmware/can/node_capture.hpp"
#include "firmware/can/node_parameters.hpp"
#include "firmware/can/shaper_design_deferral.hpp"
#include "firmware/tick/tick_task.hpp"
#include "hal/can_port.hpp"

namespace tnv::fw::can {

class TuningRequests {
 public:
  TuningRequests(TickTask& task, const HostAccess& access, CommandAck& ack, NodeParameters& params,
                 const ShaperDesignDeferral& design, NodeCapture& capture, MotionAcceptance& motion) noexcept
      : task_(task),
        access_(access),
        ack_(ack),
        params_(params),
        design_(design),
        capture_(capture),
        motion_(motion) {}
  TuningRequests(const TuningRequests&) = delete;
  TuningRequests& operator=(const TuningRequests&) = delete;

  // Each the message of the request being handled, answered here (a SHAPER
  // deferred for its design when it is handled again).
  void shaper(const hal::CanFrame& frame) noexcept;
  void excite(const hal::CanFrame& frame) noexcept;

 private:
  TickTask& task_;
  const HostAccess& access_;
  CommandAck& ack_;
  NodeParameters& params_;
  const ShaperDesignDeferral& design_;
  NodeCapture& capture_;
  MotionAcceptance& motion_;
};

}  // namespace tnv::fw::can
