#pragma once
// The Bode view's data: the frequency-response measurement of one axis'
// loop (tools/can/freq_response_run.hpp, docs/frequency-response.md), as
// `tnvctl freq-response --json` writes it:
// {"points": [{"freq_hz", "gain_db", "phase_deg", "coherence",
//              "model_gain_db", "model_phase_deg"}],
//  "margins": {"gain_db", "phase_deg", "crossover_hz", ...}, ...}.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "firmware/control/axis_model.hpp"
#include "tools/can/node_client.hpp"
#include "tools/tune/freq_response.hpp"

namespace tnv::serve {

struct FreqResponseRequest {
  std::string axis;                          // "x" | "y"
  tune::LoopKind loop = tune::LoopKind::open;  // "plant" | "open" | "closed"
  // The plant the model side uses: the emulated table's exact ZOH when the
  // node is the in-process one; otherwise the node's configured model.
  std::optional<fw::AxisModel> plant_model;
};

// Checks the request body: ApiError(400) naming what is wrong.
FreqResponseRequest parse_freq_response_request(const nlohmann::json& body);

// Runs the measurement on the node (node thread): the node must be enabled
// and holding; a refusal or bad option throws as run_freq_response does.
nlohmann::json freq_response_for_page(can_host::NodeClient& client, const FreqResponseRequest& request);

}  // namespace tnv::serve
