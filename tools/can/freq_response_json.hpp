#pragma once
// A frequency-response result as JSON (docs/frequency-response.md):
//   {"axis", "loop", "excitation", "controller", "plant_model",
//    "points": [{"freq_hz", "gain_db", "phase_deg", "coherence",
//                "model_gain_db", "model_phase_deg"}],
//    "margins": {"gain_db", "phase_deg", "crossover_hz", "phase_crossover_hz", "bandwidth_hz"},
//    "model_margins": {same keys}, "design_margins": {same keys},
//    "samples", "averages", "min_coherence"}
// A margin that does not exist (no crossing in the band) is null.
#include <nlohmann/json.hpp>

#include "tools/can/freq_response_run.hpp"

namespace tnv::can_host {

nlohmann::json freq_response_json(const FreqResponseResult& result);

}  // namespace tnv::can_host
