#pragma once
// JSON and text for `tnv-hil boring` (S4).
#include <nlohmann/json.hpp>
#include <string>

#include "tools/hil/boring_sweep.hpp"

namespace tnv::hil {

// Keys: settings, planner, bad_parts_mean, bad_parts_max, resets_mean,
// deflection_rms_mm, segments[], bad_fraction_by_part[],
// reset_fraction_by_part[], seed1 {bad_parts, resets, parts[]}.
nlohmann::json boring_sweep_json(const BoringRunRequest& request, const BoringSweepResult& result);
std::string boring_sweep_text(const BoringRunRequest& request, const BoringSweepResult& result);

}  // namespace tnv::hil
