#pragma once
// The tuning library's results (tools/tune) as JSON, for `tnvctl identify
// --json`, `tnvctl autotune --json` and `tnv-hil identify|best-circle --json`.
// Kept out of tools/tune, which depends on the firmware and Eigen only.
#include <nlohmann/json.hpp>

#include "tools/tune/axis_design.hpp"
#include "tools/tune/axis_identification.hpp"
#include "tools/tune/mode_fit.hpp"
#include "tools/tune/shaper_choice.hpp"

namespace tnv::can_host {

nlohmann::json identification_json(const tune::AxisIdentification& id);
nlohmann::json design_json(const tune::AxisDesign& d);
nlohmann::json mode_fit_json(const tune::ModeFit& fit);
nlohmann::json shaper_choice_json(const tune::ShaperChoice& choice);

}  // namespace tnv::can_host
