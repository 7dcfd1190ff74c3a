#pragma once
// The CAN node's parameters: the live set, its one path of change and
// PARAM_REQUEST (get / set / stage / commit / discard, docs/can-protocol.md).
// Every change, whatever asks for it (a set, a commit, a COMMAND, a load,
// restore_defaults), goes through apply(): the whole next set is validated,
// refused busy where it must wait for rest or for the worker, then applied
// to the task between two ticks, all of it or none of it.
//
// Each host stages into its own set (host_staged_sets.hpp); set and commit
// need command ownership, get and stage do not. Safety parameters change
// only in commissioning mode (CommissioningMode). A shaper design the node
// lacks is made on the worker first (ShaperDesignDeferral): the request is
// deferred then, and answered when it is handled again.
//
// Bounded work, no allocation, exceptions, locks or logging: it runs in
// CanNode::service(). The constructor brings the task in line with the set
// (controller per axis, enabled shapers); the task must be at rest.
#include <array>
#include <cstddef>
#include <cstdint>

#include "firmware/can/commissioning_mode.hpp"
#include "firmware/can/host_access.hpp"
#include "firmware/can/host_staged_sets.hpp"
#include "firmware/can/node_capture.hpp"
#include "firmware/can/node_settings.hpp"
#include "firmware/can/node_storage.hpp"
#include "firmware/can/node_transmit.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "firmware/can/shaper_design_cache.hpp"
#include "firmware/can/shaper_design_deferral.hpp"
#include "firmware/tick/tick_task.hpp"
#include "hal/can_port.hpp"

namespace tnv::fw::can {

class NodeParameters {
 public:
  // `settings` must pass validate(). `capture` is only referred to (the
  // node builds it after this part).
  NodeParameters(std::uint8_t node_id, TickTask& task, const HostAccess& access, CommissioningMode& commissioning,
                 NodeTransmit& tx, NodeStorage& storage, ShaperDesignDeferral& design, const NodeCapture& capture,
                 const NodeSettings& settings) noexcept;
  NodeParameters(const NodeParameters&) = delete;
  NodeParameters& operator=(const NodeParameters&) = delete;

  const NodeSettings& settings() const noexcept { return settings_; }
  // What the boring planner learned (BORE_GAUGE changes it in place): kept
  // with the parameters so that it is saved and loaded with them, but no parameter.
  BoringStationState& bore_state() noexcept { return settings_.bore_state; }

  // PARAM_REQUEST of the request being handled, answered here (unless deferred).
  void handle(const hal::CanFrame& frame) noexcept;
  // PARAM_REPLY answering the request being handled.
  void reply(ErrorCode result, std::uint16_t param, std::uint32_t value) noexcept;
  // The one path of change. `idle_touched`: the change includes a parameter
  // that applies only at rest. `may_defer`: with a worker, a shaper design
  // the cache lacks defers the request (ok returned, ShaperDesignDeferral::deferred()
  // set: the caller must not answer).
  ErrorCode apply(const NodeSettings& next, bool idle_touched, bool may_defer = true) noexcept;
  // COMMAND restore_defaults (idle only): the defaults, keeping what
  // describes this machine and this node.
  ErrorCode restore_defaults() noexcept;
  // The shaper designs the node has (a load job's and a deferral's land here).
  ShaperDesignCache& designs() noexcept { return designs_; }

  std::size_t staged_count() const noexcept { return staged_.total(); }  // all hosts
  std::size_t staged_count(std::uint8_t host) const noexcept;            // the host's own pending set
  // A save, load or shaper design in flight: the worker takes one job at a time.
  bool worker_busy() const noexcept { return storage_.pending() || design_.pending(); }

 private:
  bool capture_change_refused(const NodeSettings& next) const noexcept;

  std::uint8_t node_id_;
  TickTask& task_;
  const HostAccess& access_;
  CommissioningMode& commissioning_;
  NodeTransmit& tx_;
  NodeStorage& storage_;
  ShaperDesignDeferral& design_;
  const NodeCapture& capture_;
  NodeSettings settings_;
  const NodeSettings& defaults_;   // restore_defaults' base, computed once (cached_default_node_settings)
  ShaperDesignCache designs_{};
  HostStagedSets staged_{};
  std::array<bool, hal::kAxisCount> shaper_configured_{};
  std::uint16_t blamed_param_ = 0;  // the parameter the last invalid set was refused for
};

}  // namespace tnv::fw::can
