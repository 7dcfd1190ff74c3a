#pragma once
// What the CAN node sends unasked: the HEARTBEAT (state, fault, the error
// bits, free slots, owner), the cyclic telemetry (POSITION, FOLLOWING,
// SLIDING, OUTPUT, ARSC, CONTOUR; each every tlm.*_ms, TelemetryScheduler)
// and FAULT_EVENT, once per latched fault (docs/can-protocol.md).
//
// The heartbeat's error bits read the other parts; the few that are its own
// are kept here: the sticky jog-deadman and host-timeout bits (cleared by
// the next accepted motion request) and the counts at the last heartbeat
// (a bit says "more since then").
//
// Telemetry is droppable in the transmit queue; the heartbeat and
// FAULT_EVENT are not. Bounded work, no allocation, exceptions, locks or
// logging: it runs in CanNode::service().
#include <cstdint>

#include "firmware/can/commissioning_mode.hpp"
#include "firmware/can/host_access.hpp"
#include "firmware/can/node_capture.hpp"
#include "firmware/can/node_parameters.hpp"
#include "firmware/can/node_storage.hpp"
#include "firmware/can/node_transmit.hpp"
#include "firmware/can/program_stream.hpp"
#include "firmware/can/telemetry_scheduler.hpp"
#include "firmware/tick/tick_task.hpp"
#include "hal/can_port.hpp"

namespace tnv::fw::can {

class NodeTelemetry {
 public:
  // The counts start from the task's and the port's now. `capture` is only
  // referred to (the node builds it after this part).
  NodeTelemetry(std::uint8_t node_id, const TickTask& task, const hal::CanPort& can, NodeTransmit& tx,
                const HostAccess& access, const CommissioningMode& commissioning, const NodeStorage& storage,
                const NodeParameters& params, ProgramStream& programs, const NodeCapture& capture) noexcept;
  NodeTelemetry(const NodeTelemetry&) = delete;
  NodeTelemetry& operator=(const NodeTelemetry&) = delete;

  // `ticks` new ticks (normally 1): a new jog-deadman stop noticed; returns
  // the cyclic_bit()s of the messages due (send() them).
  std::uint32_t on_tick(std::uint64_t ticks) noexcept;
  // The owner's silence stopped the motion (sticky heartbeat bit).
  void host_timed_out() noexcept { host_timeout_ = true; }
  // A motion request was accepted: the sticky bits clear.
  void motion_accepted() noexcept {
    jog_deadman_ = false;
    host_timeout_ = false;
  }
  // FAULT_EVENT for a newly latched fault (once per latch).
  void check_fault() noexcept;
  // The frames `due` (from on_tick()), heartbeat first.
  void send(std::uint32_t due) noexcept;
  // HEARTBEAT.errors, were one sent now.
  std::uint16_t heartbeat_errors() const noexcept;
  // HEARTBEAT.axes (homed and shaper bits per axis), were one sent now.
  std::uint8_t heartbeat_axes() const noexcept;

 private:
  void send_heartbeat() noexcept;

  std::uint8_t node_id_;
  const TickTask& task_;
  const hal::CanPort& can_;
  NodeTransmit& tx_;
  const HostAccess& access_;
  const CommissioningMode& commissioning_;
  const NodeStorage& storage_;
  const NodeParameters& params_;
  ProgramStream& programs_;
  const NodeCapture& capture_;
  TelemetryScheduler telemetry_{};
  std::uint32_t deadman_stops_seen_ = 0;
  bool fault_reported_ = false;
  bool jog_deadman_ = false;   // sticky until the next accepted motion request
  bool host_timeout_ = false;  // sticky until the next accepted motion request
  std::uint64_t bus_errors_at_heartbeat_ = 0;
  std::uint64_t can_errors_at_heartbeat_ = 0;
  std::uint64_t late_ticks_at_heartbeat_ = 0;
};

}  // namespace tnv::fw::can
