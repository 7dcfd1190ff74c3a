#pragma once
// The Bode view's data: the frequency-response measurement of one axis'
// loop, as the page draws it:
// {"points": [{"freq_hz", "gain_db", "phase_deg", "coherence",
//              "model_gain_db"?, "model_phase_deg"?}],
//  "margins": {"gain_db", "phase_deg", "crossover_hz"}}.
#include <nlohmann/json.hpp>
#include <string>

#include "tools/can/node_client.hpp"

namespace tnv::serve {

inline constexpr const char* kFreqResponseMissing = "frequency response not available in this build";

struct FreqResponseRequest {
  std::string axis;  // "x" | "y"
  std::string loop;  // "speed" | "position"
};

// Checks the request body: ApiError(400) naming what is wrong.
FreqResponseRequest parse_freq_response_request(const nlohmann::json& body);

// Runs the measurement on the node (node thread). This build has none:
// ApiError(501, kFreqResponseMissing).
nlohmann::json freq_response_for_page(can_host::NodeClient& client, const FreqResponseRequest& request);

}  // namespace tnv::serve
