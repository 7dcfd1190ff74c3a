#pragma once
// COMMAND, answered by one COMMAND_ACK (code = the command code, detail =
// index of the offending field). Every check comes before anything is
// started: a refused command changes nothing. Every code needs command
// ownership except take_ownership, release_ownership, program_status and
// the broadcast stop. The codes with a part of their own go to it: the
// program codes to ProgramStream, save / load to StorageRequests,
// restore_defaults and the two parameter shortcuts (select_controller,
// shaper_enable) to NodeParameters::apply(), ownership to HostAccess,
// commissioning to CommissioningMode; the rest are TickTask commands.
// Bounded work, no allocation, exceptions, locks or logging: it runs in
// CanNode::service().
#include <cstdint>

#include "firmware/can/command_ack.hpp"
#include "firmware/can/commissioning_mode.hpp"
#include "firmware/can/host_access.hpp"
#include "firmware/can/motion_acceptance.hpp"
#include "firmware/can/node_parameters.hpp"
#include "firmware/can/program_stream.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "firmware/can/shaper_design_deferral.hpp"
#include "firmware/can/storage_requests.hpp"
#include "firmware/tick/tick_task.hpp"
#include "hal/can_port.hpp"

namespace tnv::fw::can {

class CommandRequest {
 public:
  CommandRequest(TickTask& task, HostAccess& access, CommandAck& ack, CommissioningMode& commissioning,
                 ProgramStream& programs, NodeParameters& params, const ShaperDesignDeferral& design,
                 StorageRequests& storage, MotionAcceptance& motion) noexcept
      : task_(task),
        access_(access),
        ack_(ack),
        commissioning_(commissioning),
        programs_(programs),
        params_(params),
        design_(design),
        storage_(storage),
        motion_(motion) {}
  CommandRequest(const CommandRequest&) = delete;
  CommandRequest& operator=(const CommandRequest&) = delete;

  // The COMMAND of the request being handled, answered here (save / load
  // when their job is done, a request deferred for its shaper designs when
  // it is handled again).
  void handle(const hal::CanFrame& frame) noexcept;

 private:
  // The codes with more to them than one TickTask call.
  ErrorCode zero(const hal::CanFrame& frame, std::uint8_t& detail) noexcept;
  ErrorCode home(const hal::CanFrame& frame, std::uint8_t& detail) noexcept;
  ErrorCode select_controller(const hal::CanFrame& frame, std::uint8_t& detail) noexcept;
  ErrorCode shaper_enable(const hal::CanFrame& frame, std::uint8_t& detail) noexcept;

  TickTask& task_;
  HostAccess& access_;
  CommandAck& ack_;
  CommissioningMode& commissioning_;
  ProgramStream& programs_;
  NodeParameters& params_;
  const ShaperDesignDeferral& design_;
  StorageRequests& storage_;
  MotionAcceptance& motion_;
};

}  // namespace tnv::fw::can
