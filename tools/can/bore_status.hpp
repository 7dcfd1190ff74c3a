#pragma once
// `tnvctl bore`: one part's gauge readings to the node's S4 planner and the
// next part's infeeds back, or the planner's state, with what the operator
// must see (parts counted, resets, out-of-band readings, the estimates).
// The same on the emulated node and on a real bus.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "tools/can/node_client.hpp"

namespace tnv::can_host {

struct BoreStatus {
  can::BoreOp op = can::BoreOp::query;
  int part = 0;                 // record: the part recorded
  BoreInfeed answer;            // BORE_INFEED: flags and the infeeds to cut with next
  double top_overhang_mm = 0.0;     // bore.l1_mm: where infeed_top applies
  double bottom_overhang_mm = 0.0;  // bore.l2_mm
  std::uint32_t parts = 0;      // bore.parts after the request
  std::uint32_t resets = 0;     // bore.resets
  double c_hat_mm = 0.0, alpha_hat = 0.0, beta_hat = 0.0;
};

// BORE_GAUGE record of one part's readings (diametral bore errors, mm;
// empty = the gauge had no reading). The part's number is `part`, or
// bore.parts + 1 read from the node. Refusals throw RequestError.
BoreStatus bore_record(NodeClient& client, std::optional<int> part, std::optional<double> top_mm,
                       std::optional<double> bottom_mm);
BoreStatus bore_query(NodeClient& client);
BoreStatus bore_restart(NodeClient& client);

std::string bore_status_text(const BoreStatus& status);
nlohmann::json bore_status_json(const BoreStatus& status);

}  // namespace tnv::can_host
