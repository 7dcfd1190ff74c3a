#pragma once
// BORE_GAUGE, the adaptive boring infeed planner (S4) as a node function.
// A finished part's gauge readings come in, the next part's infeeds go out
// in BORE_INFEED. The planner's learned state lives in the node's settings
// (NodeSettings::bore_state, written through NodeParameters::bore_state();
// it is no parameter), so save_params / load_params and the start-up load
// carry it with the parameters.
//
// record and restart change that state: they need command ownership and
// wait (busy) while a save or load works on the set; query is open to every
// host. Every check comes before the planner runs: a refused request
// changes nothing and names the offending field in BORE_INFEED.detail.
// The per-part work (eq. (11), the RLS updates, eq. (3) twice) is bounded
// and allocation-free: it runs in CanNode::service(), between two ticks.
#include <cstdint>

#include "firmware/can/host_access.hpp"
#include "firmware/can/node_parameters.hpp"
#include "firmware/can/node_storage.hpp"
#include "firmware/can/node_transmit.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "hal/can_port.hpp"

namespace tnv::fw::can {

class BoreGaugeRequest {
 public:
  BoreGaugeRequest(std::uint8_t node_id, const HostAccess& access, NodeTransmit& tx, NodeStorage& storage,
                   NodeParameters& params) noexcept
      : node_id_(node_id), access_(access), tx_(tx), storage_(storage), params_(params) {}
  BoreGaugeRequest(const BoreGaugeRequest&) = delete;
  BoreGaugeRequest& operator=(const BoreGaugeRequest&) = delete;

  // The BORE_GAUGE of the request being handled, answered here.
  void handle(const hal::CanFrame& frame) noexcept;
  // BORE_INFEED answering the request being handled: `flags` of a recorded
  // part (the started bit is added); the infeeds of the part to cut now.
  void reply(ErrorCode result, std::uint8_t detail, std::uint8_t flags = 0) noexcept;

 private:
  std::uint8_t node_id_;
  const HostAccess& access_;
  NodeTransmit& tx_;
  NodeStorage& storage_;
  NodeParameters& params_;
};

}  // namespace tnv::fw::can
